-- In-plane modes of a free elastic ring (no supports): three rigid-body modes, then the
-- inextensible bending modes
--   f_n = n (n^2 - 1) / (2 pi R^2 sqrt(n^2 + 1)) sqrt(EI / (rho A)),  n = 2, 3, 4, ...
-- each a degenerate pair (Hoppe 1871; Soedel, Vibrations of Shells and Plates, ch. 5).
-- This deck checks itself.
--
--   tirefe inputs/ring_modes.lua [elements=96]

local p = tirefe.parameters{
  elements = { 96, "beam elements around the ring" },
  radius = { 0.27, "ring radius R", unit = "m" },
  EI = { 20.0, "bending stiffness", unit = "N m^2" },
  rhoA = { 1.5, "mass per length", unit = "kg/m" },
}

local model = tirefe.model{ title = "Free ring modes" }
local ring = {}
for i = 0, p.elements - 1 do
  local angle = 2 * math.pi * i / p.elements
  ring[#ring + 1] = model:node{ x = p.radius * math.cos(angle), y = p.radius * math.sin(angle) }
end
-- A thin ring: axial and shear stiffness far above EI / R^2; rotary inertia of a 10 mm thick section.
model:section{ name = "ring", EA = 1e5 * p.EI / p.radius ^ 2, GA = 1e5 * p.EI / p.radius ^ 2, EI = p.EI,
               rhoA = p.rhoA, rhoI = p.rhoA * 0.01 ^ 2 / 12 }
model:beam{ section = "ring", nodes = ring, closed = true }

model:output{ file = "ring_modes.h5" }
local f = model:modal{ modes = 9, label = "free" }

local function ring_frequency(n)
  return n * (n ^ 2 - 1) / (2 * math.pi * p.radius ^ 2 * math.sqrt(n ^ 2 + 1)) * math.sqrt(p.EI / p.rhoA)
end
for mode = 1, 3 do
  tirefe.check{ name = "rigid-body mode " .. mode, value = f[mode], expected = 0, tolerance = 0 }
end
for n = 2, 4 do
  for pair = 0, 1 do
    local mode = 4 + 2 * (n - 2) + pair
    tirefe.check{ name = string.format("n = %d bending mode (%d of the pair)", n, pair + 1), value = f[mode],
                  expected = ring_frequency(n), relative = 0.015 }
  end
end
