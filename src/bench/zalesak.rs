//! The Zalesak slotted-disk rotation (004 §5.1).
