// Avenues — `avenues view ... -o FILE`: the picture of the view, chosen by FILE's extension.
// Drawings and half-tone pictures are added here as the renderers land.
#include <filesystem>

#include "app/commands.h"

namespace avenues::app {

void write_view_output(const LoadedPlan&, const ViewSetup&, const VisibleSet&, const std::string& path,
                       nlohmann::json&) {
  const std::string ext = std::filesystem::path(path).extension().string();
  throw std::runtime_error("cannot write '" + path + "': no renderer yet writes '" + ext +
                           "' files (use --overlay FILE.svg and --stats-json FILE)");
}

}  // namespace avenues::app
