// The upsample's workgroup memory for its SHARED variants: the reduced samples a 16 × 16
// workgroup's pixels read, at most SPAN_EDGE × SPAN_EDGE of them (colour, and camera
// distance: unused with LAYERS).

var<workgroup> span_colour: array<vec4<f32>, SPAN_EDGE * SPAN_EDGE>;
var<workgroup> span_distance: array<f32, SPAN_EDGE * SPAN_EDGE>;
