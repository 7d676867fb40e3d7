//! Approximation of discontinuous geometry by smooth surfaces (paper A §3, *CAGD techniques
//! for surface grid generation*, Hamann & Jean): [`coons`] builds one local approximant, a
//! projected Coons patch with multiquadric gap filling, within a stated distance of the
//! original surfaces wherever they exist.

pub mod coons;
