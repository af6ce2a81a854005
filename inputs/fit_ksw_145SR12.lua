-- Fits the effective sidewall bending stiffness k_sw of the 145 SR-12 to its vertical
-- force-deflection curve on a flat road at 208 kPa (145SR12_vertical_208kPa.csv, built
-- from Rhyne's stiffness relation), then predicts the vertical stiffness at 150 and
-- 250 kPa with the fitted value (docs/model.md section 2: k_sw is independent of pressure).
-- Measured tires and the Magic Formula pressure law put K(150)/K(208) at 0.77-0.83 and
-- K(250)/K(208) at 1.12-1.17 (docs/tire_data.md). Both signs of the k_sw term are fitted
-- (k_sw_sign = +1: eq. 9 as printed; -1: the physical bending direction). docs/fitting.md
-- discusses the result. This deck checks itself.
--
--   tirefe inputs/fit_ksw_145SR12.lua [elements=100] [step_mm=2.5]

local p = tirefe.parameters{
  elements = { 100, "wedges around the tire" },
  step_mm = { 2.5, "spindle deflection per quasi-static step", unit = "mm" },
}
local reference = tirefe.read_csv{ file = "145SR12_vertical_208kPa.csv" }

-- Vertical spindle forces [N] of the inflated tire pressed on a flat, frictionless road by
-- prescribed spindle deflections [m] (measured from first touch), in quasi-static steps
-- of step_mm that carry the solution from one deflection to the next (lua/tire_identify.lua).
local identify = require("tire_identify")
local function flat_road_forces(k_sw, k_sw_sign, pressure, deflections)
  local tire_parameters = require("tires.145SR12")
  tire_parameters.elements = p.elements
  tire_parameters.pressure = pressure
  tire_parameters.k_sw, tire_parameters.k_sw_sign = k_sw, k_sw_sign
  return identify.vertical_loads(tire_parameters, deflections, p.step_mm * 1e-3)
end

-- Vertical stiffness of a curve: the least-squares slope through the origin [N/m].
local function stiffness(deflections, forces)
  local sum_fd, sum_dd = 0, 0
  for i, d in ipairs(deflections) do sum_fd, sum_dd = sum_fd + forces[i] * d, sum_dd + d * d end
  return sum_fd / sum_dd
end

local deflections = reference.deflection
local measured = stiffness(deflections, reference.force)
print(string.format("reference: K(208 kPa) = %.1f N/mm", measured / 1e3))

local results = {}
for _, sign in ipairs{ 1, -1 } do
  local label = sign > 0 and "plus" or "minus"
  local fit = tirefe.fit{
    parameters = { { name = "k_sw", initial = 100, lower = 0, upper = 400 } },
    data_file = "145SR12_vertical_208kPa.csv", data_column = "force",
    model = function(q, curve) return flat_road_forces(q.k_sw, sign, 0.208e6, curve.deflection) end,
    tolerance = 1e-3, relative_step = 1e-3,
    output = "fit_ksw_145SR12_" .. label .. ".h5", curve_points = 21,
  }
  local k_sw = fit.values.k_sw
  local start = os.clock()
  local at_208 = stiffness(deflections, flat_road_forces(k_sw, sign, 0.208e6, deflections))
  local seconds = os.clock() - start
  local at_150 = stiffness(deflections, flat_road_forces(k_sw, sign, 0.150e6, deflections))
  local at_250 = stiffness(deflections, flat_road_forces(k_sw, sign, 0.250e6, deflections))
  results[label] = { fit = fit, k_sw = k_sw, K208 = at_208, low = at_150 / at_208, high = at_250 / at_208 }
  print(string.format("k_sw_sign %+d: %s after %d evaluations, k_sw = %.2f N m; K(208 kPa) = %.1f N/mm; "
                      .. "K(150)/K(208) = %.3f (0.77-0.83), K(250)/K(208) = %.3f (1.12-1.17); %.3f s CPU per curve",
                      sign, fit.status, fit.evaluations, k_sw, at_208 / 1e3, at_150 / at_208, at_250 / at_208, seconds))
end

-- The printed sign: a small positive k_sw reproduces the reference stiffness, and the
-- pressure scaling then lands inside the measured bands.
local plus = results.plus
tirefe.check{ name = "k_sw_sign +1: fit converged", value = plus.fit.status == "converged" and 1 or 0, expected = 1 }
tirefe.check{ name = "k_sw_sign +1: K(208 kPa) [N/mm]", value = plus.K208 / 1e3, expected = measured / 1e3, relative = 0.01 }
tirefe.check{ name = "k_sw_sign +1: K(150)/K(208) in 0.77-0.83", value = plus.low, expected = 0.80, tolerance = 0.03 }
tirefe.check{ name = "k_sw_sign +1: K(250)/K(208) in 1.12-1.17", value = plus.high, expected = 1.145, tolerance = 0.025 }
-- The physical sign only stiffens: the tire without k_sw is already as stiff as the
-- reference, so the fit holds k_sw on its lower bound 0.
local minus = results.minus
tirefe.check{ name = "k_sw_sign -1: fit held on k_sw = 0", value = minus.fit.status == "at_bound" and minus.k_sw or 1,
              expected = 0, tolerance = 1e-9 }
