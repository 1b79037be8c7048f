//! The redistancing experiments of 003 §8 (tables 8.1-8.4, volume drift).
