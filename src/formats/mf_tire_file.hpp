// Standard tire property files (.tir of MF-Tyre / MF-Swift 5.2 to 6.2, PAC2002 and the
// ADAMS layout they share) read for what a ring tire can take from them: size, inflation
// pressure, masses and inertias, the vertical load-deflection law and MF-Swift's in-plane
// structural data. The Magic Formula's force coefficients describe the contact patch's
// slip, which the ring model computes itself: those sections are passed over, and
// docs/tire.md lists every section and key, used or not.
//
// MfTireFile holds what the file states, in SI. ring_parameters() turns it into a
// model:tire parameter set: the file's size, pressure and masses, and for what a Magic
// Formula file does not describe (belt stiffnesses, sidewall length) the 145 SR-12 set
// per unit tread width. lua/tire_identify.lua then fits the ring's structural
// parameters to the stated vertical stiffness and in-plane modes (docs/tire.md).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/teim_orbit.hpp"

namespace tirefe {

struct MfTireFile {
  std::string path;
  std::string format;      // [MODEL] PROPERTY_FILE_FORMAT, or "FITTYP n", or "" when neither is given
  int dimension_line = 0;  // of [DIMENSION], for messages about its keys
  // [DIMENSION]
  double unloaded_radius = 0.0;                           // R0 [m]
  std::optional<double> width, aspect_ratio, rim_radius;  // [m], [-], [m]
  // [OPERATING_CONDITIONS] INFLPRES / NOMPRES, or [TIRE_CONDITIONS] IP / IP_NOM [Pa]
  std::optional<double> inflation_pressure, nominal_pressure;
  // [INERTIA]
  std::optional<double> mass, polar_inertia, belt_mass, belt_polar_inertia;  // kg, kg m^2
  std::optional<double> pac2002_belt_mass;  // a PAC2002 file's [ALIGNING_COEFFICIENTS] MBELT (0: not given)
  // [VERTICAL]
  std::optional<double> nominal_load, vertical_stiffness, pressure_effect,
      quadratic_stiffness;                       // FNOMIN, Cz, PFZ1, Q_FZ2
  std::vector<Eigen::Vector2d> deflection_load;  // [DEFLECTION_LOAD_CURVE]: (deflection [m], load [N])
  // [STRUCTURAL] (MF-Swift)
  std::optional<double> longitudinal_stiffness;  // [N/m]
  std::optional<double> longitudinal_frequency;  // FREQ_LONG [Hz]: belt fore-aft / vertical mode, rim held
  std::optional<double> windup_frequency;        // FREQ_WINDUP [Hz]: belt rotation against the rim
  std::optional<double> longitudinal_damping;    // DAMP_LONG [-]: damping ratio of that mode
  std::optional<double> windup_damping;          // DAMP_WINDUP [-]

  /// Reads a standard file ([MDI_HEADER] optional); formats::TeimOrbitError naming the file and
  /// line for a malformed one, a misspelt key tirefe reads, or a missing UNLOADED_RADIUS.
  static MfTireFile read(const formats::TeimOrbitFile& file, formats::TeimOrbitReader& reader);

  /// The vertical load [N] at a deflection [m] from the free radius, at inflation pressure
  /// p [Pa]: the [DEFLECTION_LOAD_CURVE] when the file has one (measured at its own
  /// pressure), otherwise the Magic Formula law
  ///   F = (1 + PFZ1 (p - NOMPRES) / NOMPRES) (Cz d + Q_FZ2 FNOMIN (d / R0)^2),
  /// Cz = VERTICAL_STIFFNESS. Nothing when the file states neither.
  std::optional<double> stated_load(double deflection, double pressure) const;
  /// The deflection [m] at which stated_load() reaches 'load'.
  std::optional<double> stated_deflection(double load, double pressure) const;
  /// The sections tirefe reads with the standard keys of each it does not use
  /// (docs/tire.md); a key of these sections spelt like one tirefe uses is refused.
  static const std::map<std::string, std::vector<std::string>>& unused_keys();
};

/// A model:tire parameter (key and SI value) with where its value comes from.
struct RingParameter {
  std::string key;
  double value;
  std::string origin;  // e.g. "[DIMENSION] UNLOADED_RADIUS", or the rule of an estimate
};

/// The ring tire of a standard file at inflation pressure 'pressure' (the file's when not
/// given; formats::TeimOrbitError when the file states none), with the pressure acting on
/// 'tread_width' (3/4 of the section width when not given; the sidewall's length follows
/// it, every other estimate scales with the section width). In model:tire's key order.
std::vector<RingParameter> ring_parameters(const MfTireFile& tire, std::optional<double> pressure,
                                           std::optional<double> tread_width = std::nullopt);

/// The pressure ring_parameters() builds at: 'pressure', else INFLPRES (IP), else NOMPRES
/// (IP_NOM); nothing when neither is known.
std::optional<double> build_pressure(const MfTireFile& tire, std::optional<double> pressure);

}  // namespace tirefe
