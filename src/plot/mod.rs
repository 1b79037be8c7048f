//! Figures drawn with plotters into PNG files.
