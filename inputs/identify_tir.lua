-- Ring tires from standard tire property files (docs/mf_tire_files.md, "Your tire from a standard
-- file"): four public MF-Tyre files (Project Chrono's HMMWV, VW microbus and FED-alpha
-- truck tires, ExternData's MF 6.1 sample; inputs/tires/README.md) and an MF-Swift 6.2 file
-- with in-plane structural data. Each is read by tirefe.read_tire, fitted by
-- lua/tire_identify.lua (the width the pressure acts on to the vertical stiffness at the
-- nominal load; with MF-Swift data also k_gamma and the sidewall bending to the belt's
-- modes on the held rim), and the built tire is compared with what the file states and with
-- what docs/mf_tire_files.md reports of it ('built': the fitted width, the load at half the nominal
-- deflection, the belt's translation and rotation modes on the held rim). The fitted rings
-- are written as tirefe tire files into the output folder. This deck checks itself.
--
--   tirefe inputs/identify_tir.lua [elements=100]

local p = tirefe.parameters{
  elements = { 100, "wedges around each tire" },
}
local identify = require("tire_identify")

-- The files, and the pressures of the two that state none in a key (their comments and
-- names do: 190000 Pa, 60 psi); 'built': w [mm], F(d/2) [N], f1 and f0 [Hz] of the fitted
-- ring as docs/mf_tire_files.md reports them.
local files = {
  { name = "HMMWV_Pac02Tire", file = "tires/HMMWV_Pac02Tire.tir",
    built = { width = 45.4, half_load = 8921, translation = 69.4, rotation = 33.7 } },
  { name = "mf_185_80R14", file = "tires/mf_185_80R14.tir", pressure = 190e3,
    built = { width = 132.9, half_load = 1955, translation = 88.2, rotation = 54.3 } },
  { name = "335_65R22_5_G275MSA_60psi", file = "tires/335_65R22_5_G275MSA_60psi.tir", pressure = 60 * 6894.757293168,
    built = { width = 193.7, half_load = 10210, translation = 80.1, rotation = 43.7 } },
  { name = "sample_mf61", file = "tires/sample_mf61.tir",
    built = { width = 122.4, half_load = 2146, translation = 71.2, rotation = 46.8 } },
  { name = "mf_swift_205_60R15", file = "tires/mf_swift_205_60R15.tir",
    built = { width = 158.6, half_load = 2151, translation = 77.0, rotation = 63.5 } },
}

local function optional(value, format, scale)
  return value and string.format(format, value * (scale or 1)) or "-"
end

print(string.format("\n  %-26s %8s %8s %8s %8s %8s %7s %7s %7s %7s %6s %6s", "file", "w [mm]", "K file", "K built",
                    "F/2 file", "F/2 built", "f1 file", "f1", "f0 file", "f0", "z1", "z0"))
for _, entry in ipairs(files) do
  local tp, stated = tirefe.read_tire{ file = entry.file, pressure = entry.pressure }
  tp.elements = p.elements
  local result = identify.fit(tp, stated)
  local m = result.measured
  print(string.format("  %-26s %8.1f %8.1f %8.1f %8.0f %8.0f %7s %7.1f %7s %7.1f %6.3f %6.3f", entry.name,
                      result.tp.tread_width * 1e3, stated.vertical_stiffness / 1e3, m.vertical_stiffness / 1e3,
                      stated.half_load or 0, m.half_load, optional(stated.longitudinal_frequency, "%.1f"),
                      m.translation, optional(stated.windup_frequency, "%.1f"), m.rotation, m.translation_damping,
                      m.rotation_damping))
  for target, residual in pairs(result.residuals) do
    print(string.format("    fit residual %-12s %+.2e (%s, %d evaluations)", target, residual, result.fit.status,
                        result.fit.evaluations))
    tirefe.check{ name = entry.name .. ": " .. target .. " residual", value = residual, expected = 0, tolerance = 1e-3 }
  end
  tirefe.check{ name = entry.name .. ": K built / K file", value = m.vertical_stiffness / stated.vertical_stiffness,
                expected = 1, tolerance = 1e-3 }
  -- As documented: the width and F(d/2) to 2 % (they move with the contact's law), the
  -- modes on the held rim to 1 % (they move with the fitted width alone).
  local built = entry.built
  tirefe.check{ name = entry.name .. ": fitted width [mm]", value = result.tp.tread_width * 1e3,
                expected = built.width, relative = 0.02 }
  tirefe.check{ name = entry.name .. ": F(d/2) built [N]", value = m.half_load, expected = built.half_load,
                relative = 0.02 }
  tirefe.check{ name = entry.name .. ": belt translation mode [Hz]", value = m.translation,
                expected = built.translation, relative = 0.01 }
  tirefe.check{ name = entry.name .. ": belt rotation mode [Hz]", value = m.rotation, expected = built.rotation,
                relative = 0.01 }
  if stated.windup_damping then
    tirefe.check{ name = entry.name .. ": belt translation damping ratio", value = m.translation_damping,
                  expected = stated.longitudinal_damping, tolerance = 0.005 }
    tirefe.check{ name = entry.name .. ": belt rotation damping ratio", value = m.rotation_damping,
                  expected = stated.windup_damping, tolerance = 0.005 }
  end
  tirefe.write_tire{ file = entry.name .. "_ring.tir", parameters = result.tp,
                     comments = { "fitted by inputs/identify_tir.lua to " .. entry.file } }
end
