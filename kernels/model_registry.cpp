#include "kernels/model_registry.hpp"

#include <utility>

#include "src/core/types.hpp"

namespace mpsolid {

namespace {
template <class Model>
ModelInfo info_of() {
  return {Model::name, Model::options_section, Model::options(), Model::uses_rotation,
          Model::rotation_invariant};
}

template <std::size_t... K>
std::vector<ModelInfo> catalog_of(std::index_sequence<K...>) {
  static_assert((BondModel<std::variant_alternative_t<K, AnyModel>> && ...));
  return {info_of<std::variant_alternative_t<K, AnyModel>>()...};
}

template <std::size_t K = 0>
AnyModel make_by_name(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                      const OptionValues& options, Range whole_rows) {
  if constexpr (K == std::variant_size_v<AnyModel>) {
    throw InputError("unknown model '" + name + "'");
  } else {
    using Model = std::variant_alternative_t<K, AnyModel>;
    if (name == Model::name) return AnyModel(std::in_place_index<K>, p, bonds, options, whole_rows);
    return make_by_name<K + 1>(name, p, bonds, options, whole_rows);
  }
}
}  // namespace

const std::vector<ModelInfo>& model_catalog() {
  static const std::vector<ModelInfo> catalog =
      catalog_of(std::make_index_sequence<std::variant_size_v<AnyModel>>());
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
