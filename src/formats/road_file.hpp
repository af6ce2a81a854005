// Road files: the 2D roads of ADAMS road data files (.rdf, TeimOrbit format), road profiles
// measured into CSV files and the ASCII OpenCRG road surfaces of ASAM (.crg), read as the
// shapes of tirefe's rigid surfaces (docs/roads.md gives the keys and the mapping).
//
// A road data file's [MODEL] METHOD = '2D' road types map onto the surfaces:
//   flat                    a flat road at height OFFSET
//   poly_line               a profile through (XZ_DATA): {x z}, {x z_l z_r} or {x_l z_l x_r z_r}
//   plank                   a profile: a step of HEIGHT from START over LENGTH, its edges
//                           cut by 45 degree bevels BEVEL_EDGE_LENGTH long
//   pot_hole                a profile: a rectangular hole DEPTH deep from START over LENGTH
//   drum                    a drum of DIAMETER with at most one cleat
// Heights are relative to the road's OFFSET. A CSV profile has a position column (x, s or
// distance) and a height column (z, height or elevation), or one per track (z_left and
// z_right, ...), names in any case, each with a length unit in its header (x_mm, "z [in]",
// "Distance (m)"; none: metres), separated by commas, semicolons or tabs.
//
// An OpenCRG file (ASAM OpenCRG, the text formats LRFI and LDFI) holds a grid of heights
// over a reference line: long sections at lateral positions v, one row per step along the
// line's length u. The plane model takes one track: the heights along u at one v (the
// reference line, v = 0, by default; between two sections linearly), plus the reference
// line's own height from its slope channel and the banking channel times v.
//
// Left and right tracks: a file with two picks one by 'track'; a file with one serves
// both. A point equal to the one before is skipped (one track may stand still while the
// other steps). Everything is in metres, in the file's own frame: placing it on the deck's
// road (start, offset) is the caller's.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "contact/rigid_surface.hpp"

namespace tirefe {

enum class RoadTrack { Left, Right };

struct RoadShape {
  enum class Kind { Flat, Profile, Drum };
  Kind kind = Kind::Profile;
  std::string road_type;                // as the file names it, e.g. "plank"
  double level = 0.0;                   // flat: the road's height [m]
  std::vector<Eigen::Vector2d> points;  // profile: the polyline of the track [m]
  double diameter = 0.0;                // drum [m]
  Cleat cleat;                          // drum; height 0: none
};

/// The 2D road of an ADAMS road data file; formats::TeimOrbitError naming the file and line for a
/// bad file, an unknown key or a road type tirefe does not model.
RoadShape read_road_data_file(const std::string& path, std::optional<RoadTrack> track);

/// A road profile from a CSV file with a header; ModelError (or fitting::CurveDataError)
/// naming the file and line otherwise.
std::vector<Eigen::Vector2d> read_road_csv(const std::string& path, std::optional<RoadTrack> track);

/// The track at lateral position v [m] (left positive) of an ASCII OpenCRG file, as (u, z)
/// points; ModelError naming the file and line for a bad file, a binary one, a modifier
/// tirefe does not apply, or a v outside the road or where the file has no heights.
std::vector<Eigen::Vector2d> read_opencrg(const std::string& path, double v);

/// A profile file by its name: .csv, .crg, or the two-column 'x y' text of RoadProfile;
/// a text file that is none of these (an OpenCRG, road data or CSV file under another
/// name) is refused with what it looks like. 'track' applies to CSV files, 'v' to OpenCRG.
std::vector<Eigen::Vector2d> read_road_profile(const std::string& path, std::optional<RoadTrack> track,
                                               std::optional<double> v);

}  // namespace tirefe
