//! Lagrange P1 and P2 elements on triangles and tetrahedra (shape functions, gradients, nodes).
