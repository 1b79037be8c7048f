//! Anisotropic mesh adaptation: metric-driven split, collapse, flip and smoothing.
