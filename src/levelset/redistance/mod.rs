//! Level-set redistancing (geometric, PPR with oblique projection, fast marching).
