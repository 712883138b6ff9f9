#include "kernels/model_registry.hpp"

#include <string_view>
#include <utility>

#include "src/core/types.hpp"

namespace mpsolid {

namespace {
template <class Model>
ModelInfo info_of() {
  return {Model::name, Model::options_section, Model::options(), Model::uses_rotation,
          Model::rotation_invariant};
}

template <class Model>
constexpr int dimension_of() {
  if constexpr (requires { Model::dimension; })
    return Model::dimension;
  else
    return 2;
}

template <std::size_t... K>
std::vector<ModelInfo> catalog_of(std::index_sequence<K...>) {
  static_assert((BondModel<std::variant_alternative_t<K, AnyModel>> && ...));
  return {info_of<std::variant_alternative_t<K, AnyModel>>()...};
}

// Each space model answers to its plane twin's name with the same options.
template <std::size_t... K>
constexpr bool space_twins_match(std::index_sequence<K...>) {
  return ((std::string_view(std::variant_alternative_t<K, AnyModel>::name) ==
               std::variant_alternative_t<K + kModelCount, AnyModel>::name &&
           dimension_of<std::variant_alternative_t<K, AnyModel>>() == 2 &&
           dimension_of<std::variant_alternative_t<K + kModelCount, AnyModel>>() == 3) &&
          ...);
}
static_assert(std::variant_size_v<AnyModel> == 2 * kModelCount &&
              space_twins_match(std::make_index_sequence<kModelCount>()));

template <std::size_t K = 0>
AnyModel make_by_name(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                      const OptionValues& options, Range whole_rows) {
  if constexpr (K == std::variant_size_v<AnyModel>) {
    throw InputError("unknown model '" + name + "'");
  } else {
    using Model = std::variant_alternative_t<K, AnyModel>;
    if (name == Model::name && p.dimension == dimension_of<Model>())
      return AnyModel(std::in_place_index<K>, p, bonds, options, whole_rows);
    return make_by_name<K + 1>(name, p, bonds, options, whole_rows);
  }
}
}  // namespace

const std::vector<ModelInfo>& model_catalog() {
  static const std::vector<ModelInfo> catalog = catalog_of(std::make_index_sequence<kModelCount>());
  return catalog;
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const ModelInfo& m : model_catalog()) names.push_back(m.name);
  return names;
}

const ModelInfo& model_info(const std::string& name) {
  for (const ModelInfo& m : model_catalog())
    if (m.name == name) return m;
  throw InputError("unknown model '" + name + "'");
}

AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const OptionValues& options) {
  return make_by_name(name, p, bonds, options, p.all());
}

AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const OptionValues& options, Range whole_rows) {
  return make_by_name(name, p, bonds, options, whole_rows);
}

}  // namespace mpsolid
