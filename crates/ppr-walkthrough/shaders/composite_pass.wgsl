// Composite of the walkthrough: the lit scene with PPR's reflection mixed in where the
// surface is reflective, tone mapped, onto the swapchain (or the screenshot target).
//
// reflected = mix(fallback, reflection.rgb, reflection.a)
// result    = mix(scene, reflected, weight)
//   reflection.a: PPR's confidence, 1 where it found a reflection well inside the screen,
//   fading towards the screen borders, 0 where it found none (a hole, or off screen);
//   fallback: what the engine has for reflections without PPR (a game samples its
//   reflection probe or sky; here a constant sky colour);
//   weight: the forward pass's reflectivity × Fresnel (0 on surfaces that reflect nothing).

struct Composite {
    // 0: final image; 1: PPR's raw reflection buffer (holes dark purple); 2: the weight;
    // 3: final image in linear HDR (not tone mapped or encoded: the next frame's PPR input).
    mode: u32,
    // 1 when the reflection texture holds this frame's PPR output (0: nothing was visible).
    reflections: u32,
    // 1 when the target is not an sRGB format: encode here.
    encode_srgb: u32,
    exposure: f32,
    // The fallback reflection, linear RGB (w unused).
    fallback: vec4<f32>,
}

@group(0) @binding(0) var<uniform> composite: Composite;
@group(0) @binding(1) var scene_color: texture_2d<f32>;
@group(0) @binding(2) var reflection: texture_2d<f32>;
@group(0) @binding(3) var reflection_weight: texture_2d<f32>;

// `vs_main`: the full-screen triangle of ppr-scene-gpu's fullscreen_triangle.wgsl.

// Narkowicz's fit of the ACES filmic curve.
fn tonemap(x: vec3<f32>) -> vec3<f32> {
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn linear_to_srgb(c: vec3<f32>) -> vec3<f32> {
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(position.xy);
    let scene = textureLoad(scene_color, p, 0).rgb;
    var found = vec4<f32>(0.0);
    if (composite.reflections == 1u) {
        found = textureLoad(reflection, p, 0);
    }
    let confidence = clamp(found.a, 0.0, 1.0);
    let weight = textureLoad(reflection_weight, p, 0).r;
    var rgb: vec3<f32>;
    switch composite.mode {
        case 1u: {
            rgb = mix(vec3<f32>(0.08, 0.0, 0.08), found.rgb, confidence);
        }
        case 2u: {
            rgb = vec3<f32>(weight);
        }
        default: {
            let reflected = mix(composite.fallback.rgb, found.rgb, confidence);
            rgb = mix(scene, reflected, clamp(weight, 0.0, 1.0));
        }
    }
    if (composite.mode == 3u) {
        return vec4<f32>(rgb, 1.0);
    }
    if (composite.mode != 2u) {
        rgb = tonemap(max(rgb, vec3<f32>(0.0)) * composite.exposure);
    }
    if (composite.encode_srgb == 1u) {
        rgb = linear_to_srgb(rgb);
    }
    return vec4<f32>(rgb, 1.0);
}
