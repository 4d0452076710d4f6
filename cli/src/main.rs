#![forbid(unsafe_code)]
#![allow(dead_code)]
mod error;
mod io;
mod mesh;
mod topology;
fn main() {}
