#include "io/frame_views.hpp"

#include <map>

namespace tirefe::io {

RowView surface_view(const std::string& surface, size_t frame) {
  return {"/surfaces/" + surface + "/frames/" + std::to_string(frame), "/surfaces/" + surface + "/outline", 0, 2, 2};
}

std::vector<RowView> frame_views(size_t frame, const std::function<bool(const std::string&)>& has,
                                 const std::vector<std::string>& surfaces) {
  const std::string prefix = "/fields/frames/" + std::to_string(frame) + "/";
  std::vector<RowView> views;
  for (const char* vector : {"displacement", "velocity", "deformation"})
    if (has(std::string("/fields/") + vector))
      views.push_back({prefix + vector, std::string("/fields/") + vector, 0, 2, 3});
  views.push_back({prefix + "rotation", "/fields/displacement", 2, 1, 0});
  for (const std::string& surface : surfaces) views.push_back(surface_view(surface, frame));
  return views;
}

size_t make_frame_views(const std::string& path) {
  Hdf5File file = Hdf5File::open_published(path);
  if (!file.exists("/fields/time") || !file.exists("/fields/displacement"))
    throw IoError("'" + path + "' holds no field frames (/fields/time, /fields/displacement): no views to make");
  const std::vector<hsize_t> times = file.shape("/fields/time");
  const size_t frames = times.empty() ? 0 : static_cast<size_t>(times[0]);
  const std::vector<std::string> surfaces =
      file.exists("/surfaces") ? file.members("/surfaces") : std::vector<std::string>{};
  // The frames' datasets grow together, flush by flush: each holds a row of every frame.
  std::map<std::string, std::vector<hsize_t>> shapes;
  const auto shape_of = [&](const std::string& dataset) -> const std::vector<hsize_t>& {
    auto found = shapes.find(dataset);
    return found != shapes.end() ? found->second : shapes[dataset] = file.shape(dataset);
  };
  std::map<std::string, bool> present;  // the same answer for every frame
  const auto has = [&](const std::string& dataset) {
    const auto [found, fresh] = present.try_emplace(dataset, false);
    if (fresh) found->second = file.exists(dataset);
    return found->second;
  };
  // Only frames that have some views already need each one looked for.
  const bool some_made = file.exists("/fields/frames");
  size_t made = 0;
  try {
    for (size_t frame = 0; frame < frames; ++frame) {
      const bool look = some_made && file.exists("/fields/frames/" + std::to_string(frame));
      for (const RowView& view : frame_views(frame, has, surfaces)) {
        if ((look || view.path.rfind("/surfaces/", 0) == 0) && file.exists(view.path)) continue;
        file.write_row_view(view.path, view.source, shape_of(view.source), frame, view.first, view.count, view.width);
        ++made;
      }
    }
  } catch (...) {
    file.abandon();  // the file stays as it was
    throw;
  }
  file.close();
  return made;
}

}  // namespace tirefe::io
