//! What every technique and preset shares: output only on reflector pixels, resizing.
