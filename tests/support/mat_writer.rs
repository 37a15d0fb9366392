//! A writer of MATLAB v5 `.mat` files for the tests that read captures
//! (tests/trace_mat.rs, tests/ballbar_tolerant_import.rs), from MathWorks'
//! "MAT-File Format" (Level 5).
#![allow(dead_code)] // each test uses its share

use miniz_oxide::deflate::compress_to_vec_zlib;

/// A writer of MAT-file Level 5, from MathWorks' format description.
pub struct Mat {
    /// Big-endian byte order.
    pub big: bool,
}

impl Mat {
    pub fn u32(&self, v: u32) -> [u8; 4] {
        if self.big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        }
    }

    pub fn header(&self) -> Vec<u8> {
        let mut h = "MATLAB 5.0 MAT-file, Platform: test, Created on: Fri Nov 27 10:00:00 2026"
            .to_string()
            .into_bytes();
        h.resize(116, b' ');
        h.extend([0u8; 8]);
        if self.big {
            h.extend(0x0100u16.to_be_bytes());
            h.extend(b"MI");
        } else {
            h.extend(0x0100u16.to_le_bytes());
            h.extend(b"IM");
        }
        h
    }

    /// A data element: tag, data, padding to 8 bytes.
    pub fn el(&self, ty: u32, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        out.extend(self.u32(ty));
        out.extend(self.u32(data.len() as u32));
        out.extend(data);
        while out.len() % 8 != 0 {
            out.push(0);
        }
        out
    }

    /// A small data element (at most 4 bytes in the tag's second word).
    pub fn small(&self, ty: u32, data: &[u8]) -> Vec<u8> {
        let mut out = self.u32(((data.len() as u32) << 16) | ty).to_vec();
        let mut d = data.to_vec();
        d.resize(4, 0);
        out.extend(d);
        out
    }

    pub fn matrix(
        &self,
        class: u32,
        flags: u32,
        dims: &[usize],
        name: &str,
        body: &[u8],
    ) -> Vec<u8> {
        let mut inner = self.el(6, &[self.u32(class | flags), self.u32(0)].concat());
        let dims: Vec<u8> = dims.iter().flat_map(|&d| self.u32(d as u32)).collect();
        inner.extend(self.el(5, &dims));
        inner.extend(self.el(1, name.as_bytes()));
        inner.extend(body);
        self.el(14, &inner)
    }

    pub fn doubles(&self, name: &str, v: &[f64]) -> Vec<u8> {
        let data: Vec<u8> = v
            .iter()
            .flat_map(|x| {
                if self.big {
                    x.to_be_bytes()
                } else {
                    x.to_le_bytes()
                }
            })
            .collect();
        self.matrix(6, 0, &[1, v.len()], name, &self.el(9, &data))
    }

    pub fn chars(&self, name: &str, s: &str) -> Vec<u8> {
        let data: Vec<u8> = s
            .encode_utf16()
            .flat_map(|c| {
                if self.big {
                    c.to_be_bytes()
                } else {
                    c.to_le_bytes()
                }
            })
            .collect();
        self.matrix(4, 0, &[1, s.len()], name, &self.el(4, &data))
    }

    /// A 1×n struct array: `elems[i]` holds one matrix (unnamed) per field.
    pub fn structure(&self, name: &str, fields: &[&str], elems: &[Vec<Vec<u8>>]) -> Vec<u8> {
        let len = 32;
        let mut names = Vec::new();
        for f in fields {
            let mut b = f.as_bytes().to_vec();
            b.resize(len, 0);
            names.extend(b);
        }
        let mut body = self.small(5, &self.u32(len as u32));
        body.extend(self.el(1, &names));
        for e in elems {
            for m in e {
                body.extend(m);
            }
        }
        self.matrix(2, 0, &[1, elems.len()], name, &body)
    }

    pub fn compressed(&self, element: &[u8]) -> Vec<u8> {
        let z = compress_to_vec_zlib(element, 6);
        let mut out = self.u32(15).to_vec();
        out.extend(self.u32(z.len() as u32));
        out.extend(z);
        out
    }
}
