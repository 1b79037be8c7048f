//! Error versus vertex count: anisotropic, isotropic-adapted and uniform meshes on one shape.
