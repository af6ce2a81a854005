#include "formats/mf_tire_file.hpp"

#include <cmath>

namespace tirefe {

namespace {

using formats::Dimension;

constexpr double kPi = 3.14159265358979323846;
constexpr Dimension kLength{1};
constexpr Dimension kForce{0, 1};
constexpr Dimension kMass{0, 0, 1};
constexpr Dimension kInertia{2, 0, 1};
constexpr Dimension kStiffness{-1, 1};  // N/m
constexpr Dimension kFrequency{0, 0, 0, -1};
constexpr Dimension kPressure{0, 0, 0, 0, 0, 1};

// The 145 SR-12 set (lua/tires/145SR12.lua; a test compares) per unit tread width: what a
// standard file does not describe scales with the tread's width from it.
constexpr double kReferenceTreadWidth = 0.110;          // m
constexpr double kReferenceTreadEA = 3.0e6;             // N
constexpr double kReferenceTreadGA = 5.0e4;             // N
constexpr double kReferenceTreadEI = 20.0;              // N m^2
constexpr double kReferenceMassPerLength = 2.2;         // kg/m
constexpr double kReferenceRotaryInertia = 7e-5;        // kg m: the belt section's, about 20 mm deep
constexpr double kReferenceShearStiffness = 2.0e4;      // k_gamma, N/m
constexpr double kReferenceSidewallDamping = 150.0;     // N s/m^2, radial and circumferential
constexpr double kReferenceRubberRadial = 3e8;          // the tread rubber's, N/m^2
constexpr double kReferenceRubberShear = 1e8;           // N/m^2
constexpr double kTreadWidthPerSectionWidth = 0.75;     // the set's 0.110 m of a 145 mm section
constexpr double kSidewallShareOfTreadPressure = 0.75;  // the set's sidewalls carry 3/4 of p w
// The TNO 205/60R15 carries 1.6-2.1 kg of its 9.3 kg off the belt (docs/tire_data.md).
constexpr double kNonBeltMassPerBeltMass = 0.25;

std::string key_of(const char* section, const char* key) { return std::string("[") + section + "] " + key; }

/// Piecewise-linear y(x) on increasing x (the first or last segment continued beyond).
double interpolate(const std::vector<Eigen::Vector2d>& points, double x, int from, int to) {
  for (size_t i = 1; i < points.size(); ++i)
    if (x <= points[i][from] || i + 1 == points.size()) {
      const Eigen::Vector2d& a = points[i - 1];
      const Eigen::Vector2d& b = points[i];
      return a[to] + (x - a[from]) / (b[from] - a[from]) * (b[to] - a[to]);
    }
  return points.front()[to];
}

}  // namespace

const std::map<std::string, std::vector<std::string>>& MfTireFile::unused_keys() {
  static const std::map<std::string, std::vector<std::string>> keys{
      {"DIMENSION", {"RIM_WIDTH", "BOTTOMING_RADIUS"}},
      {"OPERATING_CONDITIONS", {}},
      {"TIRE_CONDITIONS", {}},
      {"INERTIA", {"IXX", "BELT_IXX", "GRAVITY"}},
      {"VERTICAL",
       {"VERTICAL_DAMPING",
        "MC_CONTOUR_A",
        "MC_CONTOUR_B",
        "BREFF",
        "DREFF",
        "FREFF",
        "Q_RE0",
        "Q_V1",
        "Q_V2",
        "Q_FZ3",
        "Q_FCX",
        "Q_FCY",
        "Q_FCY2",
        "Q_CAM",
        "Q_CAM1",
        "Q_CAM2",
        "Q_CAM3",
        "Q_FYS1",
        "Q_FYS2",
        "Q_FYS3",
        "BOTTOM_OFFST",
        "BOTTOM_STIFF",
        "DYNAMIC_STIFFNESS",
        "DYNAMIC_DAMPING"}},
      {"LOADED_RADIUS_COEFFICIENTS", {"Q_RE0", "QV1", "QV2", "QFCX", "QFCY", "QFCG"}},
      {"STRUCTURAL",
       {"LATERAL_STIFFNESS", "YAW_STIFFNESS", "FREQ_LAT", "FREQ_YAW", "DAMP_LAT", "DAMP_YAW", "DAMP_RESIDUAL",
        "DAMP_VLOW", "Q_BVX", "Q_BVT", "PCFX1", "PCFX2", "PCFX3", "PCFY1", "PCFY2", "PCFY3", "PCMZ1"}}};
  return keys;
}

MfTireFile MfTireFile::read(const formats::TeimOrbitFile& file, formats::TeimOrbitReader& reader) {
  MfTireFile tire;
  tire.path = file.path();
  if (const auto format = reader.string("MODEL", "PROPERTY_FILE_FORMAT"))
    tire.format = *format;
  else if (const auto fit_type = reader.number("MODEL", "FITTYP"))
    tire.format = "FITTYP " + formats::round_trip_number(*fit_type);

  if (const formats::TeimOrbitSection* dimension = file.section("DIMENSION")) tire.dimension_line = dimension->line;
  tire.unloaded_radius = reader.required_number("DIMENSION", "UNLOADED_RADIUS", kLength, "the free tire's radius");
  tire.width = reader.number("DIMENSION", "WIDTH", kLength);
  tire.aspect_ratio = reader.number("DIMENSION", "ASPECT_RATIO");
  tire.rim_radius = reader.number("DIMENSION", "RIM_RADIUS", kLength);

  tire.inflation_pressure = reader.number("OPERATING_CONDITIONS", "INFLPRES", kPressure);
  tire.nominal_pressure = reader.number("OPERATING_CONDITIONS", "NOMPRES", kPressure);
  const auto ip = reader.number("TIRE_CONDITIONS", "IP", kPressure);
  const auto ip_nominal = reader.number("TIRE_CONDITIONS", "IP_NOM", kPressure);
  if (!tire.inflation_pressure) tire.inflation_pressure = ip;
  if (!tire.nominal_pressure) tire.nominal_pressure = ip_nominal;

  tire.mass = reader.number("INERTIA", "MASS", kMass);
  tire.polar_inertia = reader.number("INERTIA", "IYY", kInertia);
  tire.belt_mass = reader.number("INERTIA", "BELT_MASS", kMass);
  tire.belt_polar_inertia = reader.number("INERTIA", "BELT_IYY", kInertia);
  tire.pac2002_belt_mass = reader.number("ALIGNING_COEFFICIENTS", "MBELT", kMass);

  // PAC2002's scale factors of the nominal load and of the vertical stiffness (1 without).
  const double load_scale = reader.number("SCALING_COEFFICIENTS", "LFZO").value_or(1.0);
  const double stiffness_scale = reader.number("SCALING_COEFFICIENTS", "LCZ").value_or(1.0);
  tire.nominal_load = reader.number("VERTICAL", "FNOMIN", kForce);
  tire.vertical_stiffness = reader.number("VERTICAL", "VERTICAL_STIFFNESS", kStiffness);
  // The law's coefficients sit in [VERTICAL] (MF-Tyre) or [LOADED_RADIUS_COEFFICIENTS] (ADAMS);
  // a linear coefficient other than 0 gives the stiffness as Q_FZ1 FNOMIN / R0.
  const auto either = [&](const char* vertical_key, const char* loaded_radius_key) {
    const auto value = reader.number("VERTICAL", vertical_key);
    const auto other = reader.number("LOADED_RADIUS_COEFFICIENTS", loaded_radius_key);
    return value ? value : other;
  };
  const auto linear = either("Q_FZ1", "QFZ1");
  tire.quadratic_stiffness = either("Q_FZ2", "QFZ2");
  tire.pressure_effect = either("PFZ1", "PFZ1");
  if (linear && *linear != 0.0 && tire.nominal_load)
    tire.vertical_stiffness = *linear * *tire.nominal_load / tire.unloaded_radius;
  if (tire.nominal_load) *tire.nominal_load *= load_scale;
  if (tire.vertical_stiffness) *tire.vertical_stiffness *= stiffness_scale;
  if (const formats::TeimOrbitTable* curve = reader.table("DEFLECTION_LOAD_CURVE", "")) {
    for (size_t row = 0; row < curve->rows.size(); ++row) {
      const std::vector<double> deflection = reader.row_numbers(*curve, row, kLength);
      const std::vector<double> load = reader.row_numbers(*curve, row, kForce);
      if (deflection.size() != 2)
        reader.fail(curve->row_lines[row], "[DEFLECTION_LOAD_CURVE] row has " + std::to_string(deflection.size()) +
                                               " values: give the deflection and the load");
      const Eigen::Vector2d point(deflection[0], load[1]);
      if (!tire.deflection_load.empty() &&
          (point.x() <= tire.deflection_load.back().x() || point.y() <= tire.deflection_load.back().y()))
        reader.fail(curve->row_lines[row],
                    "[DEFLECTION_LOAD_CURVE]: the deflection and the load must both rise "
                    "from row to row");
      tire.deflection_load.push_back(point);
    }
    if (tire.deflection_load.size() < 2)
      reader.fail(curve->line, "[DEFLECTION_LOAD_CURVE] needs at least two rows (deflection, load)");
  }

  tire.longitudinal_stiffness = reader.number("STRUCTURAL", "LONGITUDINAL_STIFFNESS", kStiffness);
  tire.longitudinal_frequency = reader.number("STRUCTURAL", "FREQ_LONG", kFrequency);
  tire.windup_frequency = reader.number("STRUCTURAL", "FREQ_WINDUP", kFrequency);
  tire.longitudinal_damping = reader.number("STRUCTURAL", "DAMP_LONG");
  tire.windup_damping = reader.number("STRUCTURAL", "DAMP_WINDUP");

  const auto positive = [&](const char* section, const char* key, const std::optional<double>& value) {
    if (value && !(*value > 0.0))
      reader.fail(reader.line(section, key),
                  key_of(section, key) + " must be positive (got " + formats::round_trip_number(*value) + ")");
  };
  positive("DIMENSION", "UNLOADED_RADIUS", tire.unloaded_radius);
  positive("DIMENSION", "WIDTH", tire.width);
  positive("DIMENSION", "ASPECT_RATIO", tire.aspect_ratio);
  positive("DIMENSION", "RIM_RADIUS", tire.rim_radius);
  positive("SCALING_COEFFICIENTS", "LFZO", load_scale);
  positive("SCALING_COEFFICIENTS", "LCZ", stiffness_scale);
  positive("VERTICAL", "FNOMIN", tire.nominal_load);
  positive("VERTICAL", "VERTICAL_STIFFNESS", tire.vertical_stiffness);
  positive("INERTIA", "MASS", tire.mass);
  positive("INERTIA", "BELT_MASS", tire.belt_mass);
  positive("STRUCTURAL", "FREQ_LONG", tire.longitudinal_frequency);
  positive("STRUCTURAL", "FREQ_WINDUP", tire.windup_frequency);
  if (tire.rim_radius && *tire.rim_radius >= tire.unloaded_radius)
    reader.fail(reader.line("DIMENSION", "RIM_RADIUS"), "[DIMENSION] RIM_RADIUS must be below UNLOADED_RADIUS");
  reader.finish_foreign(unused_keys());
  return tire;
}

namespace {

/// The Magic Formula's vertical law F = a d + b d^2 at pressure p; nothing without a stiffness.
std::optional<std::pair<double, double>> magic_formula_law(const MfTireFile& tire, double pressure) {
  if (!tire.vertical_stiffness) return std::nullopt;
  const double factor = tire.pressure_effect && tire.nominal_pressure
                            ? 1.0 + *tire.pressure_effect * (pressure - *tire.nominal_pressure) / *tire.nominal_pressure
                            : 1.0;
  const double r0 = tire.unloaded_radius;
  return std::make_pair(factor * *tire.vertical_stiffness,
                        factor * tire.quadratic_stiffness.value_or(0.0) * tire.nominal_load.value_or(0.0) / (r0 * r0));
}

}  // namespace

std::optional<double> MfTireFile::stated_load(double deflection, double pressure) const {
  if (!deflection_load.empty()) return std::max(0.0, interpolate(deflection_load, deflection, 0, 1));
  const auto law = magic_formula_law(*this, pressure);
  if (!law) return std::nullopt;
  return law->first * deflection + law->second * deflection * deflection;
}

std::optional<double> MfTireFile::stated_deflection(double load, double pressure) const {
  if (!deflection_load.empty()) return interpolate(deflection_load, load, 1, 0);
  const auto law = magic_formula_law(*this, pressure);
  if (!law || !(law->first > 0.0)) return std::nullopt;
  const auto [a, b] = *law;
  if (b == 0.0) return load / a;
  return 2.0 * load / (a + std::sqrt(a * a + 4.0 * b * load));  // the positive root, without cancellation
}

std::optional<double> build_pressure(const MfTireFile& tire, std::optional<double> pressure) {
  if (pressure) return pressure;
  if (tire.inflation_pressure) return tire.inflation_pressure;
  return tire.nominal_pressure;
}

std::vector<RingParameter> ring_parameters(const MfTireFile& tire, std::optional<double> pressure,
                                           std::optional<double> tread_width) {
  const auto p = build_pressure(tire, pressure);
  if (!p)
    throw formats::TeimOrbitError(tire.path +
                                  ": the file states no inflation pressure ([OPERATING_CONDITIONS] INFLPRES "
                                  "or NOMPRES, [TIRE_CONDITIONS] IP): give read_tire a 'pressure'");
  const std::string dimension = tire.path + ":" + std::to_string(tire.dimension_line) + ": ";
  // Without the section width, a given tread width stands for three quarters of it.
  if (!tire.width && !tread_width)
    throw formats::TeimOrbitError(
        dimension +
        "no value of [DIMENSION] WIDTH (the section width, a length): give it, or read_tire a "
        "'tread_width' (the width the pressure acts on, about 3/4 of it)");
  const double r0 = tire.unloaded_radius;
  const double section_width = tire.width ? *tire.width : *tread_width / kTreadWidthPerSectionWidth;
  double rim_radius = 0.0;
  std::string rim_origin = "[DIMENSION] RIM_RADIUS";
  if (tire.rim_radius) {
    rim_radius = *tire.rim_radius;
  } else if (tire.aspect_ratio) {
    rim_radius = r0 - *tire.aspect_ratio * section_width;
    rim_origin = "UNLOADED_RADIUS - ASPECT_RATIO WIDTH";
  }
  if (!(rim_radius > 0.0 && rim_radius < r0))
    throw formats::TeimOrbitError(dimension +
                                  "no value of [DIMENSION] RIM_RADIUS (a length below UNLOADED_RADIUS; or "
                                  "ASPECT_RATIO, from which it follows)");

  // The set's per-width values scale with three quarters of the section width; the width
  // the pressure acts on is that too, unless the caller (a fit) gives another.
  const double nominal_width = kTreadWidthPerSectionWidth * section_width;
  const double scale = nominal_width / kReferenceTreadWidth;
  const double w = tread_width.value_or(nominal_width);
  const double circumference = 2.0 * kPi * r0;
  // The sidewall's cord is long enough that the two sidewall membranes take a share s of
  // the pressure on the tread width: n_sw (H/2) tan(theta) = s w with n_sw = 2 and the
  // chord H the rim-to-tread height; then eq. 1 gives the cord l = H alpha / sin(alpha).
  const double height = r0 - rim_radius;
  const double alpha = 0.5 * kPi - std::atan(kSidewallShareOfTreadPressure * w / height);
  const double sidewall_length = height * alpha / std::sin(alpha);

  double belt_mass = kReferenceMassPerLength * scale * circumference;
  std::string belt_origin = "estimate: the 145 SR-12 set's 2.2 kg/m per 0.110 m of tread width";
  if (tire.belt_mass) {
    belt_mass = *tire.belt_mass;
    belt_origin = "[INERTIA] BELT_MASS over the circumference";
  } else if (tire.pac2002_belt_mass && *tire.pac2002_belt_mass > 0.0) {
    belt_mass = *tire.pac2002_belt_mass;
    belt_origin = "[ALIGNING_COEFFICIENTS] MBELT over the circumference";
  }
  const double mass_per_length = belt_mass / circumference;
  double rim_mass = kNonBeltMassPerBeltMass * belt_mass;
  std::string rim_mass_origin = "estimate: a quarter of the belt mass (the tire's part beside the belt)";
  if (tire.mass && *tire.mass > belt_mass) {
    rim_mass = *tire.mass - belt_mass;
    rim_mass_origin = "[INERTIA] MASS - belt mass (the tire's part beside the belt)";
  }
  const double belt_inertia = tire.belt_polar_inertia.value_or(belt_mass * r0 * r0);
  double rim_inertia = rim_mass * rim_radius * rim_radius;
  std::string rim_inertia_origin = "estimate: that mass at the rim radius";
  if (tire.polar_inertia && *tire.polar_inertia > belt_inertia) {
    rim_inertia = *tire.polar_inertia - belt_inertia;
    rim_inertia_origin = "[INERTIA] IYY - BELT_IYY";
  }

  // Modal damping ratios on the rim-held belt modes (docs/tire.md): the rotation mode
  // zeta_0 = c_t / (2 m' w_0), the translation mode zeta_1 = (c_r + c_t) / (4 m' w_1),
  // m' the belt's mass per length; the frequencies those the file states.
  double radial_damping = kReferenceSidewallDamping * scale, circumferential_damping = radial_damping;
  std::string damping_origin = "estimate: the 145 SR-12 set's 150 N s/m^2 per 0.110 m of tread width";
  if (tire.windup_damping && tire.windup_frequency && tire.longitudinal_damping && tire.longitudinal_frequency) {
    circumferential_damping = 2.0 * *tire.windup_damping * mass_per_length * 2.0 * kPi * *tire.windup_frequency;
    radial_damping =
        std::max(0.0, 4.0 * *tire.longitudinal_damping * mass_per_length * 2.0 * kPi * *tire.longitudinal_frequency -
                          circumferential_damping);
    damping_origin = "[STRUCTURAL] DAMP_LONG, DAMP_WINDUP on FREQ_LONG, FREQ_WINDUP";
  }
  const std::string per_width = "estimate: the 145 SR-12 set per 0.110 m of tread width";
  return {{"elements", 100, "model:tire's default"},
          {"outer_diameter", 2.0 * r0, "2 [DIMENSION] UNLOADED_RADIUS"},
          {"rim_diameter", 2.0 * rim_radius, "2 " + rim_origin},
          {"tread_width", w, tread_width ? "read_tire's 'tread_width'" : "3/4 of [DIMENSION] WIDTH"},
          {"pressure", *p,
           pressure                  ? "read_tire's 'pressure'"
           : tire.inflation_pressure ? "[OPERATING_CONDITIONS] INFLPRES ([TIRE_CONDITIONS] IP)"
                                     : "[OPERATING_CONDITIONS] NOMPRES ([TIRE_CONDITIONS] IP_NOM)"},
          {"sidewall_length", sidewall_length, "the sidewalls carry 3/4 of the pressure on the tread width"},
          {"tread_EA", kReferenceTreadEA * scale, per_width},
          {"tread_GA", kReferenceTreadGA * scale, per_width},
          {"tread_EI", kReferenceTreadEI * scale, per_width},
          {"tread_mass_per_length", mass_per_length, belt_origin},
          {"tread_rotary_inertia_per_length", kReferenceRotaryInertia / kReferenceMassPerLength * mass_per_length,
           "estimate: the 145 SR-12 set's per belt mass (a section about 20 mm deep)"},
          {"k_sw", 0.0, "none until identified"},
          {"k_sw_sign", 1.0, "eq. 9 as printed"},
          {"k_gamma", kReferenceShearStiffness * scale, per_width},
          {"sidewall_radial_damping", radial_damping, damping_origin},
          {"sidewall_circumferential_damping", circumferential_damping, damping_origin},
          {"rim_mass", rim_mass, rim_mass_origin},
          {"rim_rotary_inertia", rim_inertia, rim_inertia_origin},
          {"tread_layer_radial_stiffness", kReferenceRubberRadial * scale, per_width},
          {"tread_layer_circumferential_stiffness", kReferenceRubberShear * scale, per_width}};
}

}  // namespace tirefe
