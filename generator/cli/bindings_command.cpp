// watergen bindings [PROFILE|FILE]: the binding map, every slot spelled out, as the file a
// build reads with --bindings (start an engine's own map from a profile); a file is checked
// first (a clash or a bad key exits 2 naming it).
#include <cstdio>

#include "commands.h"
#include "watergen/plan/binding_map_file.h"
#include "watergen/water/binding_profiles.h"

namespace watergen::cli {

Runner add_bindings_command(CLI::App& app, const Common& common) {
    auto map = std::make_shared<std::string>("watergen");
    app.add_option("map", *map,
                   "a profile (" + binding_profile_list() +
                       "; default watergen) or a binding map file to check and spell out");
    return [map, &common]() {
        Diagnostics ds;
        const std::optional<BindingMap> m = load_binding_map(*map, ds);
        if (!m) return stop(ds, "", RunStatus::BadInput, common);
        std::printf("%s\n", binding_map_json(*m).dump(2).c_str());
        return kOk;
    };
}

} // namespace watergen::cli
