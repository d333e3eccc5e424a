#include "identify/identified_parameter.hpp"

#include <cmath>
#include <stdexcept>

#include "base/number_text.hpp"

namespace upkie_rl {

namespace {

const IdentifiedParameter& find_parameter(std::string_view name) {
  std::string known;
  for (const IdentifiedParameter& parameter : kIdentifiedParameters) {
    if (parameter.name == name) return parameter;
    if (parameter.not_fittable.empty())
      known += (known.empty() ? "" : ", ") + std::string(parameter.name);
  }
  throw std::invalid_argument("--param " + std::string(name) +
                              ": unknown parameter; known: " + known);
}

double parse_bound(const std::string& text, const std::string& where) {
  const std::optional<double> value = number_from_text<double>(text);
  if (!value || !std::isfinite(*value)) {
    throw std::invalid_argument(where + ": \"" + text + "\" is not a number");
  }
  return *value;
}

}  // namespace

ParameterRequest parse_parameter_request(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const IdentifiedParameter& parameter = find_parameter(name);
  const std::string where = "--param " + name;
  if (!parameter.not_fittable.empty()) {
    throw std::invalid_argument(where +
                                ": cannot be fitted: " + std::string(parameter.not_fittable));
  }
  ParameterRequest request{&parameter, parameter.low, parameter.high};
  if (equals == std::string::npos) return request;
  const std::string range = text.substr(equals + 1);
  const std::size_t colon = range.find(':');
  if (colon == std::string::npos) {
    throw std::invalid_argument(where + ": expected NAME=LOW:HIGH, got \"" + text + "\"");
  }
  request.low = parse_bound(range.substr(0, colon), where);
  request.high = parse_bound(range.substr(colon + 1), where);
  if (!(request.low < request.high)) {
    throw std::invalid_argument(where + ": LOW must be below HIGH, got " + range);
  }
  if (request.low < parameter.low || request.high > parameter.high) {
    throw std::invalid_argument(where + ": range " + range + " leaves the declared range [" +
                                shortest_text(parameter.low) + ", " +
                                shortest_text(parameter.high) + "]");
  }
  return request;
}

std::vector<ParameterRequest> parse_parameter_requests(const std::vector<std::string>& texts) {
  std::vector<ParameterRequest> requests;
  const std::vector<std::string> defaults = {"mass_scale", "floor_friction", "action_delay",
                                             "action_lag"};
  for (const std::string& text : texts.empty() ? defaults : texts) {
    ParameterRequest request = parse_parameter_request(text);
    for (const ParameterRequest& other : requests) {
      if (other.parameter == request.parameter) {
        throw std::invalid_argument("--param " + std::string(request.parameter->name) +
                                    " is given twice");
      }
    }
    requests.push_back(request);
  }
  return requests;
}

}  // namespace upkie_rl
