//! Medit `.sol` solution files: `SolAtVertices` with one or more fields of type 1 (scalar),
//! 2 (vector) or 3 (symmetric tensor), as read and written by MMG and FreeFem++.
//!
//! Tensor component order in the file (the Medit convention, checked against MMG's
//! `MMG5_readDoubleSol3D`, which swaps slots 2 and 3 into its internal `xx xy xz yy yz zz`):
//! 2D `xx xy yy`; 3D `xx xy yy xz yz zz`. [`SolField::Tensor3`] keeps the file order.

use super::atomic::atomic_write;
use super::medit::{is_keyword, read_header_keyword, skip_section};
use super::textout::Out;
use super::tokens::{read_text, shorten, Tokens};
use crate::error::{Error, Result};
use crate::metric::{Sym2, Sym3};
use std::path::Path;

/// One field of a solution file, one entry per vertex.
#[derive(Debug, Clone, PartialEq)]
pub enum SolField {
    /// Type 1.
    Scalar(Vec<f64>),
    /// Type 2; in 2D only the first two components are used (the third is 0).
    Vector(Vec<[f64; 3]>),
    /// Type 3 in 2D: `xx xy yy`.
    Tensor2(Vec<Sym2>),
    /// Type 3 in 3D, in file order `[xx, xy, yy, xz, yz, zz]`.
    Tensor3(Vec<[f64; 6]>),
}

impl SolField {
    /// Number of vertices the field covers.
    pub fn len(&self) -> usize {
        match self {
            SolField::Scalar(v) => v.len(),
            SolField::Vector(v) => v.len(),
            SolField::Tensor2(v) => v.len(),
            SolField::Tensor3(v) => v.len(),
        }
    }

    /// Whether the field is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The Medit type code (1, 2 or 3).
    pub fn type_code(&self) -> u8 {
        match self {
            SolField::Scalar(_) => 1,
            SolField::Vector(_) => 2,
            SolField::Tensor2(_) | SolField::Tensor3(_) => 3,
        }
    }

    fn components(&self, dim: usize) -> usize {
        match self {
            SolField::Scalar(_) => 1,
            SolField::Vector(_) => dim,
            SolField::Tensor2(_) => 3,
            SolField::Tensor3(_) => 6,
        }
    }

    fn push_values(&self, v: usize, dim: usize, out: &mut Vec<f64>) {
        match self {
            SolField::Scalar(s) => out.push(s[v]),
            SolField::Vector(x) => out.extend_from_slice(&x[v][..dim]),
            SolField::Tensor2(m) => out.extend_from_slice(&[m[v].xx, m[v].xy, m[v].yy]),
            SolField::Tensor3(m) => out.extend_from_slice(&m[v]),
        }
    }
}

/// A solution file: its dimension and its fields (all of the same length).
#[derive(Debug, Clone, PartialEq)]
pub struct Sol {
    /// Space dimension (2 or 3).
    pub dim: usize,
    /// The fields, in file order.
    pub fields: Vec<SolField>,
}

impl Sol {
    /// A 2D solution with one scalar field.
    pub fn scalar(values: Vec<f64>) -> Sol {
        Sol {
            dim: 2,
            fields: vec![SolField::Scalar(values)],
        }
    }

    /// A 2D solution with one metric (tensor) field.
    pub fn metric(values: Vec<Sym2>) -> Sol {
        Sol {
            dim: 2,
            fields: vec![SolField::Tensor2(values)],
        }
    }

    /// A 3D solution with one metric (tensor) field, written in the Medit order
    /// `xx xy yy xz yz zz`.
    pub fn metric3(values: &[Sym3]) -> Sol {
        Sol {
            dim: 3,
            fields: vec![SolField::Tensor3(values.iter().map(sym3_to_file).collect())],
        }
    }

    /// A solution of dimension `dim` with one scalar field.
    pub fn scalar_dim(dim: usize, values: Vec<f64>) -> Sol {
        Sol {
            dim,
            fields: vec![SolField::Scalar(values)],
        }
    }

    /// Number of vertices (0 without fields).
    pub fn n_vertices(&self) -> usize {
        self.fields.first().map_or(0, SolField::len)
    }
}

/// The 3D tensor of a `.sol` entry in file order `[xx, xy, yy, xz, yz, zz]`.
pub fn sym3_from_file(a: &[f64; 6]) -> Sym3 {
    Sym3::new(a[0], a[1], a[3], a[2], a[4], a[5])
}

/// The file order `[xx, xy, yy, xz, yz, zz]` of a 3D tensor.
pub fn sym3_to_file(m: &Sym3) -> [f64; 6] {
    [m.xx, m.xy, m.yy, m.xz, m.yz, m.zz]
}

/// Parses a `.sol` text; with `expected = Some(n)` the vertex count must be `n` (the error
/// names the line of the count).
pub fn parse_sol(path: &Path, text: &str, expected: Option<usize>) -> Result<Sol> {
    let mut tk = Tokens::new(path, text, Some(b'#'));
    let mut dim = 0usize;
    let mut out: Option<Sol> = None;
    while let Some((kw, line)) = tk.next_token() {
        if !is_keyword(kw) {
            return Err(tk.err(format!(
                "unexpected '{}' where a keyword was expected (a count smaller than its data?)",
                shorten(kw)
            )));
        }
        if kw.eq_ignore_ascii_case("End") {
            break;
        }
        match read_header_keyword(&mut tk, kw)? {
            Some(0) => continue,
            Some(d) => {
                dim = d;
                continue;
            }
            None => {}
        }
        if !kw.eq_ignore_ascii_case("SolAtVertices") {
            skip_section(&mut tk);
            continue;
        }
        if dim == 0 {
            return Err(tk.err_at(line, "SolAtVertices before Dimension"));
        }
        if out.is_some() {
            return Err(tk.err_at(line, "second SolAtVertices section"));
        }
        out = Some(read_sol_at_vertices(&mut tk, dim, expected)?);
    }
    out.ok_or_else(|| Error::parse(path, tk.token_line(), "no SolAtVertices section"))
}

/// The data of a `SolAtVertices` section in dimension `dim`: vertex count (must equal
/// `expected` if given), field count and types, then the values vertex by vertex.
fn read_sol_at_vertices(tk: &mut Tokens, dim: usize, expected: Option<usize>) -> Result<Sol> {
    let n = tk.count("number of vertices")?;
    if let Some(m) = expected {
        if m != n {
            return Err(tk.err(format!(
                "the solution has {n} vertices but the mesh has {m}"
            )));
        }
    }
    let types = read_field_types(tk)?;
    let cap = tk.capacity(n, 2);
    let mut fields: Vec<SolField> = types
        .iter()
        .map(|&t| match (t, dim) {
            (1, _) => SolField::Scalar(Vec::with_capacity(cap)),
            (2, _) => SolField::Vector(Vec::with_capacity(cap)),
            (_, 2) => SolField::Tensor2(Vec::with_capacity(cap)),
            _ => SolField::Tensor3(Vec::with_capacity(cap)),
        })
        .collect();
    for v in 0..n {
        for (k, f) in fields.iter_mut().enumerate() {
            let what = || format!("vertex {} of {n}, field {}", v + 1, k + 1);
            let mut x = [0.0f64; 6];
            for c in x.iter_mut().take(f.components(dim)) {
                *c = tk.real_with(&what)?;
            }
            match f {
                SolField::Scalar(s) => s.push(x[0]),
                SolField::Vector(s) => s.push([x[0], x[1], if dim == 3 { x[2] } else { 0.0 }]),
                SolField::Tensor2(s) => s.push(Sym2::new(x[0], x[1], x[2])),
                SolField::Tensor3(s) => s.push(x),
            }
        }
    }
    Ok(Sol { dim, fields })
}

/// The field count (at least one) and the type of each field (1 scalar, 2 vector, 3 tensor).
fn read_field_types(tk: &mut Tokens) -> Result<Vec<u8>> {
    let nf = tk.count("number of fields")?;
    if nf == 0 {
        return Err(tk.err("SolAtVertices with no fields"));
    }
    let mut types = Vec::with_capacity(nf.min(64));
    for k in 0..nf {
        let t: i64 = tk.int(&format!("type of field {}", k + 1))?;
        if !(1..=3).contains(&t) {
            return Err(tk.err(format!(
                "field {}: unsupported solution type {t} (1 scalar, 2 vector, 3 tensor)",
                k + 1
            )));
        }
        types.push(t as u8);
    }
    Ok(types)
}

/// Reads a `.sol` file.
pub fn read_sol(path: &Path) -> Result<Sol> {
    parse_sol(path, &read_text(path)?, None)
}

/// Reads a `.sol` file whose vertex count must be `n_vertices` (that of the mesh it goes with).
pub fn read_sol_for(path: &Path, n_vertices: usize) -> Result<Sol> {
    parse_sol(path, &read_text(path)?, Some(n_vertices))
}

/// Checks that a solution can be written: dimension 2 or 3, at least one field, equal lengths,
/// tensors matching the dimension, finite values.
fn check_sol(path: &Path, sol: &Sol) -> Result<()> {
    let bad = |msg: String| Error::InvalidField {
        name: path.display().to_string(),
        msg,
    };
    if sol.dim != 2 && sol.dim != 3 {
        return Err(bad(format!("dimension {} (expected 2 or 3)", sol.dim)));
    }
    if sol.fields.is_empty() {
        return Err(bad("no fields".into()));
    }
    let n = sol.n_vertices();
    let mut vals = Vec::new();
    for (k, f) in sol.fields.iter().enumerate() {
        if f.len() != n {
            return Err(bad(format!(
                "field {} has {} values, field 1 has {n}",
                k + 1,
                f.len()
            )));
        }
        match (f, sol.dim) {
            (SolField::Tensor2(_), 3) | (SolField::Tensor3(_), 2) => {
                return Err(bad(format!(
                    "field {}: tensor does not match dimension",
                    k + 1
                )))
            }
            _ => {}
        }
        for v in 0..n {
            vals.clear();
            f.push_values(v, sol.dim, &mut vals);
            if vals.iter().any(|x| !x.is_finite()) {
                return Err(bad(format!(
                    "field {}: non-finite value at vertex {v}",
                    k + 1
                )));
            }
        }
    }
    Ok(())
}

/// Writes a `.sol` file (atomically) in the layout MMG and FreeFem++ read.
pub fn write_sol(path: &Path, sol: &Sol) -> Result<()> {
    check_sol(path, sol)?;
    let n = sol.n_vertices();
    atomic_write(path, |w| {
        let mut o = Out::new(w);
        o.text("MeshVersionFormatted 2\n\nDimension ");
        o.int(sol.dim);
        o.text("\n\nSolAtVertices\n");
        o.int(n);
        o.text("\n");
        o.int(sol.fields.len());
        for f in &sol.fields {
            o.text(" ");
            o.int(f.type_code());
        }
        o.line()?;
        let mut vals = Vec::with_capacity(16);
        for v in 0..n {
            vals.clear();
            for f in &sol.fields {
                f.push_values(v, sol.dim, &mut vals);
            }
            for (k, x) in vals.iter().enumerate() {
                if k > 0 {
                    o.text(" ");
                }
                o.real(*x);
            }
            o.line()?;
        }
        o.text("\nEnd\n");
        o.finish()
    })
}
