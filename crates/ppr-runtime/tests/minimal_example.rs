//! The minimal integration (`examples/minimal.rs`) runs on the test adapter, reflects the
//! red wall in the grey floor, and is what `docs/integration.md` quotes, line for line.

#[path = "../examples/minimal.rs"]
mod minimal;

fn device() -> (wgpu::Device, wgpu::Queue) {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default())).expect(
        "no GPU adapter found: GPU tests need one (Mesa's llvmpipe through wgpu's GL backend works \
         without a GPU)",
    );
    pollster::block_on(
        adapter.request_device(&wgpu::DeviceDescriptor {
            required_limits: adapter.limits(),
            ..Default::default()
        }),
    )
    .expect("the adapter refused a device")
}

#[test]
fn the_minimal_example_reflects_the_wall_in_the_floor() {
    let (device, queue) = device();
    let frame = minimal::render(&device, &queue).expect("the example renders");
    let [w, h] = minimal::SIZE;
    let at = |x: u32, y: u32| frame.pixels[(y * w + x) as usize];
    let red = |p: [f32; 4]| p[3] > 0.0 && (p[0] - 0.9).abs() < 0.02 && p[1] < 0.15 && p[2] < 0.15;
    // The wall's base is a horizon across the screen: the floor below it mirrors the
    // wall (red), the wall above it reflects nothing (alpha 0, as cleared).
    let reflected = frame.pixels.iter().filter(|&&p| red(p)).count();
    let anything = frame.pixels.iter().filter(|p| p[3] > 0.0).count();
    eprintln!("{reflected} red reflections of {anything} reflected pixels ({w} x {h})");
    assert!(reflected > (w * h / 8) as usize, "{reflected}");
    // Nothing but the wall is there to reflect: the rest are bilinear blends at its edges.
    assert!(reflected * 10 >= anything * 9, "{reflected} of {anything}");
    assert!((0..w).all(|x| at(x, 2)[3] == 0.0), "the wall reflects nothing");
    // Down the middle column: wall (nothing), then the floor mirroring the wall, then the
    // floor near the camera, whose reflected rays pass over the wall into the empty sky.
    assert!(red(at(w / 2, h * 2 / 3)), "the floor mirrors the wall");
    assert_eq!(at(w / 2, h - 2)[3], 0.0, "above the wall there is nothing to reflect");
}

#[test]
fn integration_md_quotes_the_example_verbatim() {
    let example = include_str!("../examples/minimal.rs");
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/integration.md"))
        .expect("docs/integration.md beside the crates");
    let begin =
        example.find("// [integration:begin]\n").expect("begin marker") + "// [integration:begin]\n".len();
    let end = example.find("    // [integration:end]").expect("end marker");
    let quoted: String = example[begin..end]
        .lines()
        .map(|l| l.strip_prefix("    ").unwrap_or(l))
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        doc.contains(&quoted),
        "docs/integration.md must quote examples/minimal.rs between its markers, unindented:\n{quoted}"
    );
}
