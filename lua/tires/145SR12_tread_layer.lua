-- 145 SR-12 with the tread-rubber layer: the paper's model (tires/145SR12.lua) plus the
-- tread rubber between the belt and the road, calibrated in two steps (docs/calibration.md):
-- the loaded fixed-axle modes (inputs/loaded_modes_145SR12.lua) showed which value moves
-- which mode; the drum-cleat run itself (inputs/drum_cleat.lua) then set the values so that
-- the spindle forces ring at the measured 88 Hz (on the cleat), 85 Hz (after it) and 35 Hz
-- (fore-aft). Units SI.
local set = {}
for key, value in pairs(require("tires.145SR12")) do set[key] = value end

-- Tread rubber, 12 mm from belt to road (8 mm tread + undertread and cap), 0.077 m of
-- rubber across the 0.110 m width (30 % grooves). Shear: an effective modulus of 0.44 MPa,
-- about half the compound's 1 MPa, as block bending and siping soften tread blocks in
-- shear; this is the value fitted to the 35 Hz.
set.tread_layer_circumferential_stiffness = 2.8e6  -- N/m^2, G_eff w / h
set.tread_layer_radial_stiffness = 4.0e7           -- N/m^2, confined compression (E = 3G, shape factor 0.6)
-- About half of the tread rubber moves with the road side.
set.tread_layer_mass_per_length = 0.4              -- kg/m
-- Hysteresis of tread compound, loss factor about 0.15 near 100 Hz: c = 0.15 k / (2 pi 100 Hz).
set.tread_layer_radial_damping = 1.0e4             -- N s/m^2
set.tread_layer_circumferential_damping = 800      -- N s/m^2
-- Belt, cap plies and the rest of the tread: 2.4 kg/m in all, 4.1 kg of the tire's
-- about 5.5 kg (the paper's set had 2.2 kg/m); sets the vertical mode.
set.tread_mass_per_length = 2.0                    -- kg/m
-- Sidewall shear: the hub-fixed wind-up mode at 62 Hz, inside the 59-68 Hz of passenger
-- tires (TNO 205/60R15), instead of 53 Hz.
set.k_gamma = 3.0e4                                -- N/m per rad
return set
