-- 145 SR-12 passenger tire (the paper's test tire), first parameter set.
-- Size from the size code; structure from published data for similar tires
-- (../docs/tire.md gives each value's origin). Calibrated against the drum-cleat
-- frequencies in docs/tire.md. Units SI.
return {
  elements = 100,
  outer_diameter = 0.543,      -- size code: 304.8 + 2 x 0.82 x 145 mm
  rim_diameter = 0.3048,       -- 12 in bead seat
  tread_width = 0.110,         -- about 3/4 of the 145 mm section width
  pressure = 0.208e6,          -- the paper's inflation pressure
  sidewall_length = 0.140,     -- meridian cord, 1.18 x the 0.119 m rim-to-tread height (belt in tension)
  tread_EA = 3.0e6,            -- steel belt, two plies
  tread_GA = 5.0e4,
  tread_EI = 20.0,             -- N m^2, order of the prototype's value
  tread_mass_per_length = 2.2, -- 3.8 kg of belt and tread over 1.7 m
  tread_rotary_inertia_per_length = 7e-5,
  tread_curvature_damping = 0.0,
  k_sw = 100.0,                -- N m, eq. 9 sign as printed (k_sw_sign = +1)
  k_sw_sign = 1,
  k_gamma = 2.0e4,             -- N/m per rad
  sidewall_radial_damping = 150.0,
  sidewall_circumferential_damping = 150.0,
  rim_mass = 8.0,
  rim_rotary_inertia = 0.1,
  -- The tread rubber the tire touches the road through (docs/tire.md; the paper's contact
  -- is a penalty on the belt nodes). In compression, a grooved tread confined between belt
  -- and road: a compression modulus of about 40 MPa (E (1 + 2 S^2), E about 4 MPa, blocks of
  -- shape factor S about 2) over 10 mm of rubber, 0.077 m of it across the tread (E_c w / h).
  -- In shear stiff, as the paper's belt nodes stick to the road: 10 x the rubber's G w / h.
  -- No damping of its own, as the paper's model has none there.
  tread_layer_radial_stiffness = 3e8,          -- N/m^2
  tread_layer_circumferential_stiffness = 1e8, -- N/m^2
}
