//! Fixed capacities of the area-light records (the kernel allocates nothing, so lists have
//! a compile-time size).

/// Capacity of a polygon light (larger polygons are split into fans by the std side).
pub const MAX_VERTICES: usize = 16;

/// Capacity of a band's breakpoint list: two crossings for each edge of the largest
/// polygon plus the two ends of the half circle.
pub const MAX_BREAKPOINTS: usize = 2 * MAX_VERTICES + 2;

/// Capacity of a sphere's breakpoint list: the two crossings of its cone and the two ends
/// of the half circle.
pub const SPHERE_BREAKPOINTS: usize = 4;

/// Capacity of the extent rule's lists of band offsets (`Breakpoints`): per polygon edge a
/// vertex, a horizon crossing and a tangency of the band, the range's two ends, and the
/// specular cuts (5 at each of two crossings).
pub const MAX_CUTS: usize = 3 * MAX_VERTICES + 12;
