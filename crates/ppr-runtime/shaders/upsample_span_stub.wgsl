// The upsample's workgroup arrays for its per-pixel variants, which never touch them
// (SHARED is false there): one element each, so that those pipelines declare no span.

var<workgroup> span_colour: array<vec4<f32>, 1>;
var<workgroup> span_distance: array<f32, 1>;
