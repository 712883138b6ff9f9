#include "python/bindings/case_handle.hpp"

#include "src/solver/case_loader.hpp"

namespace mpsolid::python {

CaseHandle CaseHandle::from_file(const std::string& path) {
  CaseHandle c;
  c.path_ = path;
  c.source_name_ = path;
  c.spec_ = c.read({});
  return c;
}

CaseHandle CaseHandle::from_text(const std::string& toml_text, const std::string& source_name) {
  CaseHandle c;
  c.text_ = toml_text;
  c.source_name_ = source_name;
  c.spec_ = c.read({});
  return c;
}

void CaseHandle::set(const std::string& key, const std::string& toml_value) {
  std::vector<std::string> with = overrides_;
  with.push_back(key + "=" + toml_value);
  CaseSpec spec = read(with);  // throws before anything changes
  spec_ = std::move(spec);
  overrides_ = std::move(with);
}

CaseSpec CaseHandle::read(const std::vector<std::string>& overrides) const {
  return path_ ? load_case(*path_, overrides) : load_case_text(text_, source_name_, overrides);
}

}  // namespace mpsolid::python
