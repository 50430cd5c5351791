// The projection's occupancy pad (bench only, ProjectionVariant::occupancy_pad_kib):
// workgroup memory that no frame uses, so that fewer of the projection's workgroups fit on
// a multiprocessor at once. Timing the pass with it says how much its time owes to how many
// workgroups run side by side. Touched only where no viewport is (the driver keeps it).

var<workgroup> occupancy_pad: array<u32, OCCUPANCY_PAD_WORDS>;

fn touch_occupancy_pad(lid: u32) {
    if (frame.size.x == 0xffffffffu) {
        occupancy_pad[lid] = lid;
        if (occupancy_pad[(lid + 1u) % OCCUPANCY_PAD_WORDS] == 7u) {
            atomicStore(&intermediate[0], 0u);
        }
    }
}
