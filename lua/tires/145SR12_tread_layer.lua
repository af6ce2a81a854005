-- 145 SR-12 with the tread-rubber layer on its drum-rig wheel: the paper's model
-- (tires/145SR12.lua) plus the tread rubber between the belt and the road and the
-- rotating inertia of the rig's wheel, hub and bearing (docs/calibration.md gives each
-- value's origin and what it does to the ringing of the rolling tire). Units SI.
local set = {}
for key, value in pairs(require("tires.145SR12")) do set[key] = value end

-- Tread rubber, 10 mm from belt to road, 0.077 m of rubber across the 0.110 m tread
-- (30 % grooves). Shear: a tread compound's modulus, G = 1.3 MPa (Shore A 60-65), k = G w / h.
set.tread_layer_circumferential_stiffness = 1.0e7  -- N/m^2
-- Radial: the tread blocks and the crown's flattening across the tread width, which the
-- plane belt cannot show, set so that the contact patch at 3800 N reaches the length of a
-- real footprint (about 0.1 m on the drum instead of the plane belt's 0.07 m).
set.tread_layer_radial_stiffness = 1.0e7           -- N/m^2
-- About half of the tread rubber moves with the road side.
set.tread_layer_mass_per_length = 0.4              -- kg/m
-- Hysteresis of tread compound, loss factor 0.15 near 100 Hz: c = 0.15 k / (2 pi 100 Hz).
set.tread_layer_radial_damping = 2.4e3             -- N s/m^2
set.tread_layer_circumferential_damping = 2.4e3    -- N s/m^2
-- Belt, cap plies and the rest of the tread: 2.4 kg/m in all with the layer's 0.4, 4.1 kg
-- of the tire's about 5.5 kg (the paper's set has 2.2 kg/m).
set.tread_mass_per_length = 2.0                    -- kg/m
-- Sidewall shear: the hub-fixed wind-up mode at 62 Hz, inside the 59-68 Hz of passenger
-- tires (TNO 205/60R15), instead of 53 Hz.
set.k_gamma = 3.0e4                                -- N/m per rad
-- What turns with the tire on the rig's dead axle: a 12 in steel wheel (0.07-0.09), the
-- beads and lower sidewalls (about 0.02), hub, bearing and brake drum (0.03-0.05).
set.rim_rotary_inertia = 0.15                      -- kg m^2
return set
