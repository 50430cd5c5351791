//! Format tests: round trips, refusal of broken files with named fields, the JSON Schema.

use glam::{DVec2, DVec3};
use ppr_format::{FORMAT_VERSION, FormatError, Reflector, ReflectorKind, ReflectorSet, ValidatedSet};
use proptest::prelude::*;

fn sample_set() -> ReflectorSet {
    let mut set = ReflectorSet::new("level.glb");
    set.source.hash = "blake3:00ff".into();
    set.extractor.name = "ppr-extract".into();
    set.extractor.version = "0.1.0".into();
    set.extractor.params.insert("min_area".into(), serde_json::json!(0.01));
    let mut floor = Reflector::new(
        0,
        "floor",
        ReflectorKind::Opaque,
        DVec3::ZERO,
        DVec3::Y,
        DVec3::X,
        DVec2::new(4.0, 3.0),
    );
    floor.coverage = 0.75;
    floor.roughness = 0.35;
    floor.occluders = vec![1];
    floor.source.nodes = vec!["Floor".into()];
    floor.source.materials = vec!["polished".into()];
    let mut mirror = Reflector::new(
        7,
        "mirror wall",
        ReflectorKind::Transparent,
        DVec3::new(0.0, 1.5, -6.0),
        DVec3::Z,
        DVec3::X,
        DVec2::new(3.0, 1.5),
    );
    mirror.parallel_group = 1;
    mirror.enabled = false;
    set.reflectors = vec![floor, mirror];
    set
}

/// Loads `json` and returns the invalid field's (reflector index, field name) or panics.
fn refused_field(json: &str) -> (Option<usize>, String) {
    let err = ReflectorSet::from_json_str(json).expect_err("a broken set must be refused");
    let f = err.invalid_field().unwrap_or_else(|| panic!("expected an invalid field, got: {err}"));
    (f.reflector.as_ref().map(|r| r.index), f.field.clone())
}

fn mutate(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut v = serde_json::to_value(sample_set()).unwrap();
    edit(&mut v);
    v.to_string()
}

#[test]
fn round_trip_through_text_and_file() {
    let set = sample_set();
    let text = set.to_json_string().unwrap();
    assert_eq!(ReflectorSet::from_json_str(&text).unwrap(), set);

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("level.ppr.json");
    set.save(&path).unwrap();
    assert_eq!(ReflectorSet::load(&path).unwrap(), set);
    // Nothing but the file itself is left in the directory.
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
    assert_eq!(names, vec![std::ffi::OsString::from("level.ppr.json")]);
}

#[test]
fn the_facing_is_the_normal_given_whatever_the_in_plane_axis() {
    // A floor seen from above faces +Y for any in-plane axis: the constructor derives
    // axis_v from the normal, so swapped axes cannot turn a reflector around.
    for u in [DVec3::X, DVec3::NEG_X, DVec3::Z, DVec3::NEG_Z] {
        let r = Reflector::new(0, "floor", ReflectorKind::Opaque, DVec3::ZERO, DVec3::Y, u, DVec2::ONE);
        assert_eq!(r.normal, DVec3::Y);
        assert!(
            (r.axis_u.cross(r.axis_v) - DVec3::Y).length() < 1e-12,
            "u {u}: frame {} {}",
            r.axis_u,
            r.axis_v
        );
        assert!(r.signed_distance(DVec3::new(0.0, 1.0, 0.0)) > 0.0);
        let mut set = ReflectorSet::new("level.glb");
        set.reflectors.push(r);
        ValidatedSet::new(set).expect("a right-handed unit frame is valid");
    }
    // An in-plane axis that is not in the plane is refused by validation.
    let mut set = ReflectorSet::new("level.glb");
    set.reflectors.push(Reflector::new(
        0,
        "tilted",
        ReflectorKind::Opaque,
        DVec3::ZERO,
        DVec3::Y,
        DVec3::new(0.6, 0.8, 0.0),
        DVec2::ONE,
    ));
    let err = ValidatedSet::new(set).expect_err("axis_u not orthogonal to the normal");
    assert!(err.field_path().is_some_and(|f| f.starts_with("reflectors[0].")), "{err}");
}

#[test]
fn invalid_fields_are_named() {
    type Edit = Box<dyn FnOnce(&mut serde_json::Value)>;
    let cases: Vec<(&str, Edit, Option<usize>, &str)> = vec![
        (
            "non-unit u",
            Box::new(|v| v["reflectors"][1]["axis_u"] = serde_json::json!([1.2, 0, 0])),
            Some(1),
            "axis_u",
        ),
        (
            "non-orthogonal v",
            Box::new(|v| v["reflectors"][0]["axis_v"] = serde_json::json!([0.6, 0, -0.8])),
            Some(0),
            "axis_v",
        ),
        (
            "flipped normal",
            Box::new(|v| v["reflectors"][0]["normal"] = serde_json::json!([0, 0, 1])),
            Some(0),
            "normal",
        ),
        (
            "zero extent",
            Box::new(|v| v["reflectors"][0]["half_extents"] = serde_json::json!([0, 1])),
            Some(0),
            "half_extents",
        ),
        (
            "negative extent",
            Box::new(|v| v["reflectors"][1]["half_extents"] = serde_json::json!([1, -2])),
            Some(1),
            "half_extents",
        ),
        (
            "coverage above 1",
            Box::new(|v| v["reflectors"][0]["coverage"] = serde_json::json!(1.5)),
            Some(0),
            "coverage",
        ),
        (
            "roughness above 1",
            Box::new(|v| v["reflectors"][1]["roughness"] = serde_json::json!(1.25)),
            Some(1),
            "roughness",
        ),
        (
            "negative roughness",
            Box::new(|v| v["reflectors"][0]["roughness"] = serde_json::json!(-0.01)),
            Some(0),
            "roughness",
        ),
        (
            "occluder out of range",
            Box::new(|v| v["reflectors"][0]["occluders"] = serde_json::json!([5])),
            Some(0),
            "occluders[0]",
        ),
        (
            "self occluder",
            Box::new(|v| v["reflectors"][1]["occluders"] = serde_json::json!([1])),
            Some(1),
            "occluders[0]",
        ),
        (
            "repeated occluder",
            Box::new(|v| v["reflectors"][1]["occluders"] = serde_json::json!([0, 0])),
            Some(1),
            "occluders[1]",
        ),
        ("duplicate id", Box::new(|v| v["reflectors"][1]["id"] = serde_json::json!(0)), Some(1), "id"),
        (
            "a wall in the floor's parallel group",
            Box::new(|v| v["reflectors"][1]["parallel_group"] = serde_json::json!(0)),
            Some(1),
            "parallel_group",
        ),
        (
            "far away centre",
            Box::new(|v| v["reflectors"][0]["center"] = serde_json::json!([2e7, 0, 0])),
            Some(0),
            "center",
        ),
    ];
    for (what, edit, index, field) in cases {
        let (got_index, got_field) = refused_field(&mutate(edit));
        assert_eq!((got_index, got_field.as_str()), (index, field), "{what}");
    }
}

#[test]
fn a_parallel_group_holds_only_reflectors_facing_the_same_way() {
    // The runtime's parallel rule lets only the nearest reflector of a group reflect a
    // pixel: a group mixing orientations loses reflections, so it is refused on load.
    let tilted = |deg: f64| {
        let mut set = sample_set();
        let mut step = set.reflectors[0].clone();
        step.id = 9;
        step.name = "step".into();
        step.center.y = 0.5;
        step.occluders.clear();
        let (s, c) = deg.to_radians().sin_cos();
        step.axis_u = DVec3::new(c, s, 0.0);
        step.normal = step.axis_u.cross(step.axis_v);
        set.reflectors.push(step);
        set
    };
    // Within the extractor's tolerance (1 degree), and at the limit, the set is valid.
    assert!(tilted(1.0).validate().is_ok());
    assert!(tilted(ppr_format::PARALLEL_GROUP_MAX_ANGLE_DEG * 0.99).validate().is_ok());
    for deg in [ppr_format::PARALLEL_GROUP_MAX_ANGLE_DEG * 1.01, 45.0, 90.0, 180.0] {
        let err = tilted(deg).validate().expect_err("a tilted reflector in the floor's group");
        assert_eq!(err.field_path().as_deref(), Some("reflectors[2].parallel_group"), "{deg}: {err}");
        let msg = err.to_string();
        assert!(msg.contains("\"step\"") && msg.contains("\"floor\""), "{msg}");
    }
    // A ceiling (the floor turned over) shares the floor's plane orientation but not its
    // reflecting side: a group of its own.
    let mut set = sample_set();
    let mut ceiling = set.reflectors[0].clone();
    ceiling.id = 9;
    ceiling.occluders.clear();
    ceiling.axis_v = DVec3::Z;
    ceiling.normal = DVec3::NEG_Y;
    set.reflectors.push(ceiling);
    assert_eq!(set.validate().unwrap_err().field_path().as_deref(), Some("reflectors[2].parallel_group"));
    set.reflectors[2].parallel_group = 2;
    set.validate().expect("own group");
}

#[test]
fn error_messages_name_file_reflector_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.ppr.json");
    std::fs::write(&path, mutate(|v| v["reflectors"][1]["axis_u"] = serde_json::json!([2, 0, 0]))).unwrap();
    let msg = ReflectorSet::load(&path).unwrap_err().to_string();
    assert!(msg.contains("broken.ppr.json"), "{msg}");
    assert!(msg.contains("reflectors[1]") && msg.contains("mirror wall") && msg.contains("axis_u"), "{msg}");
}

#[test]
fn header_problems_are_refused_first() {
    let wrong_version = mutate(|v| {
        v["version"] = serde_json::json!(FORMAT_VERSION + 1);
        v["reflectors"][0]["brand_new_field"] = serde_json::json!(1);
    });
    assert!(matches!(ReflectorSet::from_json_str(&wrong_version), Err(FormatError::UnknownVersion { .. })));
    let no_version = mutate(|v| {
        v.as_object_mut().unwrap().remove("version");
    });
    assert!(matches!(ReflectorSet::from_json_str(&no_version), Err(FormatError::UnknownVersion { .. })));
    let not_a_set = r#"{"asset": {"version": "2.0"}}"#;
    assert!(matches!(ReflectorSet::from_json_str(not_a_set), Err(FormatError::WrongFormat { .. })));
    assert!(matches!(ReflectorSet::from_json_str("{ nope"), Err(FormatError::Json(_))));
    let unknown_field = mutate(|v| v["reflectors"][0]["colour"] = serde_json::json!("red"));
    let msg = ReflectorSet::from_json_str(&unknown_field).unwrap_err().to_string();
    assert!(msg.contains("colour"), "{msg}");
    let missing = ReflectorSet::load("/definitely/not/here.ppr.json").unwrap_err().to_string();
    assert!(missing.contains("/definitely/not/here.ppr.json"), "{missing}");
}

#[test]
fn a_refused_save_leaves_the_old_file_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("level.ppr.json");
    let good = sample_set();
    good.save(&path).unwrap();
    let before = std::fs::read(&path).unwrap();
    let mut bad = good.clone();
    bad.reflectors[0].half_extents.x = f64::NAN;
    assert!(bad.save(&path).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), before);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "no temporary file left behind");
    // Writing into a directory that does not exist fails without creating anything.
    assert!(good.save(dir.path().join("missing/level.ppr.json")).is_err());
}

// ---- Roughness and version 1 ------------------------------------------------------

/// A version-1 file as `ppr-extract` wrote them before roughness was recorded.
const VERSION_1_FILE: &str = r#"{
  "format": "ppr-reflector-set",
  "version": 1,
  "source": { "path": "level.glb", "hash": "" },
  "extractor": { "name": "ppr-extract", "version": "0.1.0", "params": {} },
  "reflectors": [
    {
      "id": 3, "name": "floor", "kind": "opaque", "enabled": true,
      "center": [0.0, 0.0, 0.0], "axis_u": [1.0, 0.0, 0.0], "axis_v": [0.0, 0.0, -1.0],
      "half_extents": [2.0, 1.0], "normal": [0.0, 1.0, 0.0], "coverage": 1.0,
      "parallel_group": 0, "occluders": [], "source": { "nodes": ["Floor"] }
    }
  ]
}"#;

#[test]
fn a_version_1_file_reads_with_mirror_roughness_and_is_written_as_the_current_version() {
    assert_eq!(FORMAT_VERSION, 2);
    let set = ReflectorSet::from_json_str(VERSION_1_FILE).expect("version 1 still reads");
    assert_eq!(set.version, FORMAT_VERSION, "upgraded on reading");
    assert_eq!(set.reflectors[0].roughness, 0.0, "version 1 described perfect mirrors");
    let text = set.to_json_string().unwrap();
    let written: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(written["version"], serde_json::json!(FORMAT_VERSION));
    assert_eq!(written["reflectors"][0]["roughness"], serde_json::json!(0.0));
    assert_eq!(ReflectorSet::from_json_str(&text).unwrap(), set);
    // The schema describes both versions.
    let old: serde_json::Value = serde_json::from_str(VERSION_1_FILE).unwrap();
    assert!(schema().is_valid(&old), "the schema accepts a version-1 file");
    assert!(schema().is_valid(&written), "the schema accepts its version-2 rewrite");
    // Version 0 and versions after this build's are refused as such.
    for version in [0, FORMAT_VERSION + 1] {
        let text = VERSION_1_FILE.replace("\"version\": 1,", &format!("\"version\": {version},"));
        let err = ReflectorSet::from_json_str(&text).unwrap_err();
        assert!(matches!(err, FormatError::UnknownVersion { .. }), "{version}: {err}");
        assert!(err.to_string().contains("reads versions 1 to 2"), "{err}");
    }
}

#[test]
fn roughness_round_trips_and_bad_values_name_reflector_and_field() {
    let mut set = sample_set();
    for (r, roughness) in set.reflectors.iter_mut().zip([0.0, 1.0]) {
        r.roughness = roughness;
    }
    let text = set.to_json_string().unwrap();
    assert_eq!(ReflectorSet::from_json_str(&text).unwrap(), set, "0 and 1 are valid");
    set.reflectors[1].roughness = 0.123_456_789_012_345_67;
    let back = ReflectorSet::from_json_str(&set.to_json_string().unwrap()).unwrap();
    assert_eq!(back.reflectors[1].roughness.to_bits(), set.reflectors[1].roughness.to_bits());
    for bad in [f64::NAN, f64::INFINITY, -1e-12, 1.000_000_1] {
        set.reflectors[1].roughness = bad;
        let err = set.validate().unwrap_err();
        assert_eq!(err.field_path().as_deref(), Some("reflectors[1].roughness"), "{bad}: {err}");
        let msg = err.to_string();
        assert!(msg.contains("mirror wall") && msg.contains("roughness"), "{msg}");
        assert!(set.to_json_string().is_err(), "{bad} is not written");
    }
    // Written by hand: a string, null (JSON's NaN) or a number out of range.
    for bad in [serde_json::json!("0.2"), serde_json::Value::Null, serde_json::json!(2)] {
        let text = mutate(|v| v["reflectors"][1]["roughness"] = bad.clone());
        let err = ReflectorSet::from_json_str(&text).unwrap_err();
        let path = err.field_path().unwrap_or_default();
        assert!(path.starts_with("reflectors[1].roughness"), "{bad}: {err}");
    }
}

// ---- JSON Schema -------------------------------------------------------------------

fn schema() -> jsonschema::Validator {
    let schema: serde_json::Value = serde_json::from_str(ppr_format::JSON_SCHEMA).expect("schema is JSON");
    jsonschema::validator_for(&schema).expect("schema compiles")
}

#[test]
fn schema_accepts_what_serde_writes_and_refuses_broken_shapes() {
    let validator = schema();
    let written: serde_json::Value = serde_json::from_str(&sample_set().to_json_string().unwrap()).unwrap();
    let errors: Vec<String> = validator.iter_errors(&written).map(|e| e.to_string()).collect();
    assert!(errors.is_empty(), "{errors:?}");
    for broken in [
        mutate(|v| v["reflectors"][0]["kind"] = serde_json::json!("glossy")),
        mutate(|v| v["reflectors"][0]["half_extents"] = serde_json::json!([0, 1])),
        mutate(|v| v["reflectors"][0]["center"] = serde_json::json!([0, 1])),
        mutate(|v| v["version"] = serde_json::json!(FORMAT_VERSION + 1)),
        mutate(|v| v["reflectors"][0]["roughness"] = serde_json::json!(1.5)),
        mutate(|v| v["reflectors"][0]["roughness"] = serde_json::json!("rough")),
        mutate(|v| v["reflectors"][0]["extra"] = serde_json::json!(true)),
    ] {
        let value: serde_json::Value = serde_json::from_str(&broken).unwrap();
        assert!(!validator.is_valid(&value), "schema accepted {broken}");
        assert!(ReflectorSet::from_json_str(&broken).is_err(), "loader accepted {broken}");
    }
}

// ---- Properties --------------------------------------------------------------------

fn unit_frame() -> impl Strategy<Value = (DVec3, DVec3)> {
    (0.0..std::f64::consts::TAU, -1.0f64..1.0, 0.0..std::f64::consts::TAU).prop_map(|(phi, z, spin)| {
        let r = (1.0 - z * z).sqrt();
        let n = DVec3::new(r * phi.cos(), z, r * phi.sin());
        let any = if n.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
        let a = n.cross(any).normalize();
        let b = n.cross(a);
        let u = a * spin.cos() + b * spin.sin();
        (u, n.cross(u).normalize())
    })
}

prop_compose! {
    fn reflector()(
        id in 0u32..1000,
        name in "[a-z ]{0,12}",
        kind in prop::sample::select(ReflectorKind::ALL.to_vec()),
        enabled in any::<bool>(),
        center in prop::array::uniform3(-1e6f64..1e6),
        (u, v) in unit_frame(),
        half in prop::array::uniform2(1e-4f64..1e4),
        coverage in 0.0f64..=1.0,
        roughness in 0.0f64..=1.0,
        group in 0u32..50,
        nodes in prop::collection::vec("[A-Za-z0-9_]{1,8}", 0..3),
    ) -> Reflector {
        let mut r = Reflector::new(id, name, kind, DVec3::from(center), u.cross(v), u, DVec2::from(half));
        r.enabled = enabled;
        r.coverage = coverage;
        r.roughness = roughness;
        r.parallel_group = group;
        r.source.nodes = nodes;
        r
    }
}

prop_compose! {
    fn valid_set()(mut reflectors in prop::collection::vec(reflector(), 0..12), seed in any::<u64>()) -> ReflectorSet {
        let n = reflectors.len() as u32;
        for (i, r) in reflectors.iter_mut().enumerate() {
            r.id = i as u32 * 3 + (seed % 3) as u32; // unique
            // Random orientations: a group of their own each (shared groups are tested above).
            r.parallel_group = r.parallel_group * 16 + i as u32;
            r.occluders = (0..n).filter(|&o| o != i as u32 && (seed >> (o % 64)) & 1 == 1).collect();
        }
        let mut set = ReflectorSet::new("level.glb");
        set.reflectors = reflectors;
        set
    }
}

/// One way of breaking an invariant, applied to reflector `i` of a non-empty set.
#[derive(Debug, Clone)]
enum Breakage {
    ScaleAxis(f64),
    TiltV(f64),
    Extent(f64),
    Coverage(f64),
    Roughness(f64),
    OccluderOutOfRange(u32),
    NanCenter,
}

fn breakage() -> impl Strategy<Value = Breakage> {
    prop_oneof![
        prop_oneof![0.0f64..0.999, 1.001f64..10.0].prop_map(Breakage::ScaleAxis),
        prop_oneof![-1.0f64..-0.01, 0.01f64..1.0].prop_map(Breakage::TiltV),
        prop_oneof![Just(0.0), Just(f64::NAN), Just(f64::INFINITY), -1e3f64..0.0].prop_map(Breakage::Extent),
        prop_oneof![Just(f64::NAN), -1.0f64..-1e-9, 1.0000001f64..5.0].prop_map(Breakage::Coverage),
        prop_oneof![Just(f64::NAN), Just(f64::NEG_INFINITY), -1.0f64..-1e-9, 1.0000001f64..5.0]
            .prop_map(Breakage::Roughness),
        (0u32..100).prop_map(Breakage::OccluderOutOfRange),
        Just(Breakage::NanCenter),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_valid_set_survives_save_then_load(set in valid_set()) {
        let text = set.to_json_string().unwrap();
        prop_assert_eq!(ReflectorSet::from_json_str(&text).unwrap(), set);
    }

    #[test]
    fn any_broken_invariant_is_refused(set in valid_set(), pick in any::<prop::sample::Index>(), how in breakage()) {
        prop_assume!(!set.reflectors.is_empty());
        let mut set = set;
        let n = set.reflectors.len() as u32;
        let i = pick.index(set.reflectors.len());
        let r = &mut set.reflectors[i];
        let field = match how {
            Breakage::ScaleAxis(s) => { r.axis_u *= s; "axis_u" }
            Breakage::TiltV(t) => { r.axis_v = (r.axis_v + r.axis_u * t).normalize(); "axis_v" }
            Breakage::Extent(e) => { r.half_extents.y = e; "half_extents" }
            Breakage::Coverage(c) => { r.coverage = c; "coverage" }
            Breakage::Roughness(x) => { r.roughness = x; "roughness" }
            Breakage::OccluderOutOfRange(k) => { r.occluders = vec![n + k]; "occluders[0]" }
            Breakage::NanCenter => { r.center.y = f64::NAN; "center" }
        };
        // The in-memory check names reflector and field...
        let err = set.validate().unwrap_err();
        let f = err.invalid_field().expect("an invalid-field error");
        prop_assert_eq!(f.reflector.as_ref().map(|r| r.index), Some(i));
        prop_assert_eq!(f.field.as_str(), field);
        prop_assert!(set.to_json_string().is_err());
        // ...and so does the loader (JSON writes NaN and infinity as `null`, a shape error).
        let json = serde_json::to_string(&set).unwrap();
        let err = ReflectorSet::from_json_str(&json).unwrap_err();
        let expected = format!("reflectors[{i}].{field}");
        let path = err.field_path().unwrap_or_default();
        prop_assert!(path.starts_with(&expected), "{} does not name {}", err, expected);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Floats survive save then load to the last bit (serde_json's `float_roundtrip`), so
    /// reopening a set in the inspector changes nothing.
    #[test]
    fn floats_round_trip_bit_for_bit(x in prop::num::f64::NORMAL, y in -1e6f64..1e6) {
        let mut set = sample_set();
        set.reflectors[0].center = DVec3::new(x.clamp(-1e6, 1e6), y, x.abs().min(1e6) * 1e-7);
        set.reflectors[0].coverage = (y.abs() / 1e6).min(1.0);
        let back = ReflectorSet::from_json_str(&set.to_json_string().unwrap()).unwrap();
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        prop_assert_eq!(bits(back.reflectors[0].center), bits(set.reflectors[0].center));
        prop_assert_eq!(back.reflectors[0].coverage.to_bits(), set.reflectors[0].coverage.to_bits());
    }
}
