//! The curve schemes of the crate and their stable codes and names (the table of the
//! [module documentation](super)).

/// A curve subdivision scheme. The discriminants are stable codes of the C ABI
/// (`NLS_CURVE_*`), never reused.
///
/// `#[non_exhaustive]`: a later version may add a variant, so a `match` outside this crate
/// needs a wildcard arm; [`CurveScheme::ALL`] lists every scheme.
#[repr(u32)]
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CurveScheme {
    /// The linear interpolating 4-point scheme of Dyn, Levin and Gregory with `w = 1/16`
    /// ([`four_point`](super::four_point)).
    FourPoint = 0,
    /// The cubic B-spline scheme (Chaikin–Lane–Riesenfeld, degree 3), end points kept on open
    /// curves ([`bspline`](super::bspline)).
    BSpline = 1,
    /// The Möbius interpolating scheme of seed 000 §4.4.1: edge points by F4
    /// ([`mobius`](super::mobius)).
    MobiusInterpolating = 2,
    /// The Möbius approximating scheme of seed 000 §4.4.1: edge points by F4, vertex points
    /// by F4 of the two old neighbours and the two new edge points
    /// ([`mobius`](super::mobius)).
    MobiusApproximating = 3,
    /// The circle blend of seed 003 §2 ([`circle_blend`](super::circle_blend)).
    CircleBlend = 4,
    /// Differential-space subdivision (seed 001 §3.5) with the 4-point scheme on the
    /// differential polygon ([`differential`](super::differential)).
    DifferentialFourPoint = 5,
    /// Differential-space subdivision (seed 001 §3.5) with the cubic B-spline scheme on the
    /// differential polygon ([`differential`](super::differential)).
    DifferentialBSpline = 6,
}

impl CurveScheme {
    /// Every scheme, in code order.
    pub const ALL: [CurveScheme; 7] = [
        CurveScheme::FourPoint,
        CurveScheme::BSpline,
        CurveScheme::MobiusInterpolating,
        CurveScheme::MobiusApproximating,
        CurveScheme::CircleBlend,
        CurveScheme::DifferentialFourPoint,
        CurveScheme::DifferentialBSpline,
    ];

    /// The stable numeric code.
    pub const fn code(self) -> u32 {
        self as u32
    }

    /// The scheme of a numeric code, or `None` for an unassigned code.
    pub fn from_code(code: u32) -> Option<CurveScheme> {
        CurveScheme::ALL.iter().copied().find(|s| s.code() == code)
    }

    /// The name used by the command line and in reports: `four-point`, `bspline`, `mobius-interpolating`, `mobius-approximating`,
    /// `circle-blend`, `differential-four-point`, `differential-bspline`.
    pub const fn name(self) -> &'static str {
        match self {
            CurveScheme::FourPoint => "four-point",
            CurveScheme::BSpline => "bspline",
            CurveScheme::MobiusInterpolating => "mobius-interpolating",
            CurveScheme::MobiusApproximating => "mobius-approximating",
            CurveScheme::CircleBlend => "circle-blend",
            CurveScheme::DifferentialFourPoint => "differential-four-point",
            CurveScheme::DifferentialBSpline => "differential-bspline",
        }
    }

    /// The scheme of a name from [`CurveScheme::name`]; `differential` is accepted as
    /// [`CurveScheme::DifferentialFourPoint`].
    pub fn from_name(name: &str) -> Option<CurveScheme> {
        if name == "differential" {
            return Some(CurveScheme::DifferentialFourPoint);
        }
        CurveScheme::ALL.iter().copied().find(|s| s.name() == name)
    }

    /// Whether this build contains the scheme: the crate's `curves` feature, and `mobius` too
    /// for the two Möbius schemes. [`subdivide`](super::subdivide) refuses the others with
    /// [`Status::SchemeNotBuilt`](crate::Status::SchemeNotBuilt), and the optimiser drops
    /// their rules from its dispatch.
    pub const fn is_built(self) -> bool {
        let mobius = matches!(
            self,
            CurveScheme::MobiusInterpolating | CurveScheme::MobiusApproximating
        );
        cfg!(feature = "curves") && (!mobius || cfg!(feature = "mobius"))
    }

    /// Whether the scheme keeps the old points (bit for bit) at the even output indices.
    pub const fn is_interpolating(self) -> bool {
        matches!(
            self,
            CurveScheme::FourPoint | CurveScheme::MobiusInterpolating | CurveScheme::CircleBlend
        )
    }

    /// Whether points of a circle stay on that circle (up to rounding).
    pub const fn is_circle_preserving(self) -> bool {
        matches!(
            self,
            CurveScheme::MobiusInterpolating
                | CurveScheme::MobiusApproximating
                | CurveScheme::CircleBlend
        )
    }
}
