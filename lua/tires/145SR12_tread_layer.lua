-- 145 SR-12 with the tread-rubber layer: the paper's model (tires/145SR12.lua) plus the
-- tread rubber's compliance between the belt and the road, calibrated against the measured
-- loaded fixed-axle modes (88 Hz vertical, 35 Hz fore-aft: inputs/loaded_modes_145SR12.lua).
-- docs/calibration.md gives the origin of each value. Units SI.
local set = {}
for key, value in pairs(require("tires.145SR12")) do set[key] = value end

-- Tread rubber: compound G = 1 MPa, 10 mm from belt to road (8 mm tread + undertread),
-- 0.077 m of rubber across the 0.110 m width (30 % grooves).
set.tread_layer_circumferential_stiffness = 7.6e6  -- N/m^2, G w / h
set.tread_layer_radial_stiffness = 4.0e7           -- N/m^2, confined compression (E = 3G, shape factor 0.6)
-- About half of the 0.89 kg/m of tread rubber moves with the road side; the belt keeps the rest.
set.tread_layer_mass_per_length = 0.4              -- kg/m
set.tread_mass_per_length = 2.2 - 0.4              -- kg/m, same total mass as the paper's set
-- Sidewall shear: the hub-fixed wind-up mode at 62 Hz, inside the 59-68 Hz of passenger
-- tires (TNO 205/60R15), instead of 53 Hz.
set.k_gamma = 3.0e4                                -- N/m per rad
return set
