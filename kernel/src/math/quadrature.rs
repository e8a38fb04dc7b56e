//! Gauss–Legendre rules on [−1, 1], stored as their positive halves (the rules are
//! symmetric): node `±X[k]` has weight `W[k]`. Values: the standard tables (Abramowitz &
//! Stegun Table 25.4), to f32 precision.

/// 4-point nodes (positive half).
pub const GL4_X: [f32; 2] = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
/// 4-point weights matching [`GL4_X`].
pub const GL4_W: [f32; 2] = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];

/// 8-point nodes (positive half).
pub const GL8_X: [f32; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// 8-point weights matching [`GL8_X`].
pub const GL8_W: [f32; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];
