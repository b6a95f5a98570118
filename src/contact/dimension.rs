//! The size `Q` of a contact node's unknowns `q` as a nalgebra dimension
//! ([`kinematics`](super::kinematics)): `Const<N>` for the producers of a
//! fixed size, `Dyn` for those whose coupling is known at run time only,
//! and the one allocator bound the driver's generics carry.

use nalgebra::allocator::Allocator;
use nalgebra::{Dim, U1, U2, U3};

/// The allocations a `q`-dimension `Q` needs (`Q`-vectors, `Q × Q`, `3 × Q`,
/// `2 × Q` and their transposes), as one bound: `DefaultAllocator:
/// QAllocator<Q>`. `Q` is nalgebra's `Const<N>` for the producers of a
/// fixed size (a rigid obstacle, `U3`; a primary triangle, `Const<21>`),
/// stack-allocated on the hot path, or `Dyn` for a producer whose
/// coupling size is known at run time only (dual mortar: a secondary
/// node's weighted gap couples dozens of nodes).
pub trait QAllocator<Q: Dim>:
    Allocator<Q>
    + Allocator<Q, Q>
    + Allocator<U3, Q>
    + Allocator<Q, U3>
    + Allocator<U1, Q>
    + Allocator<U2, Q>
    + Allocator<Q, U2>
{
}

impl<Q: Dim, A> QAllocator<Q> for A where
    A: Allocator<Q>
        + Allocator<Q, Q>
        + Allocator<U3, Q>
        + Allocator<Q, U3>
        + Allocator<U1, Q>
        + Allocator<U2, Q>
        + Allocator<Q, U2>
{
}

/// The size of a dimension known at compile time (`N` of `Const<N>`), 0
/// for `Dyn`: the shape of the zero blocks of a node without kinematics.
pub fn natural_dim<Q: Dim>() -> Q {
    Q::from_usize(Q::try_to_usize().unwrap_or(0))
}
