//! Derivative recovery from P1 fields: gradients and Hessians on vertex patches.
