#include "runtime/common/godot_params.hpp"

#include <cmath>

#include <fmt/core.h>

#include "runtime/common/job_checks.hpp"

namespace crtforge::detail {

Result<nlohmann::json> godot_params_json(const std::map<std::string, Value>& params) {
    nlohmann::json json = nlohmann::json::object();
    for (const auto& [name, value] : params) {
        if (const double* d = std::get_if<double>(&value)) {
            if (!std::isfinite(*d)) return job_error(fmt::format("param '{}' is not finite", name), "params");
            json[name] = *d;
        } else if (const int64_t* i = std::get_if<int64_t>(&value)) {
            json[name] = *i;
        } else if (const bool* b = std::get_if<bool>(&value)) {
            json[name] = *b;
        } else if (const Color* c = std::get_if<Color>(&value)) {
            for (double v : *c)
                if (!std::isfinite(v)) return job_error(fmt::format("param '{}' has a colour channel that is not finite", name), "params");
            json[name] = {(*c)[0], (*c)[1], (*c)[2]};
        } else {
            return job_error(fmt::format("param '{}' is an enum name; Godot uniforms take the enum's index as an int", name),
                             "params");
        }
    }
    return json;
}

}  // namespace crtforge::detail
