// Python values as TOML (py_toml.h).
#include "python/py_toml.h"

#include <toml++/toml.h>

#include <cctype>
#include <sstream>
#include <variant>

#include "core/error.h"

namespace mirage::python {

namespace py = pybind11;

namespace {

[[noreturn]] void refuse(const std::string& what, const std::string& key, py::handle value) {
    throw MirageError(what + ": '" + key + "' is a " +
                      std::string(py::str(py::type::of(value).attr("__name__"))) +
                      "; TOML holds tables (dict), arrays (list), str, int, float and bool");
}

// A numpy scalar's kind: 'b' bool, 'i'/'u' integer, 'f' float; 0 for anything else.
char numpyKind(py::handle v) {
    if (!py::hasattr(v, "dtype") || !py::hasattr(v, "item")) return 0;
    const std::string kind = py::str(v.attr("dtype").attr("kind"));
    return kind.size() == 1 && std::string("biuf").find(kind[0]) != std::string::npos ? kind[0] : 0;
}

// A value as TOML holds it. `allowTables`: whether dicts may appear (a scene document; not an
// override's value).
using Node = std::variant<bool, int64_t, double, std::string, toml::array, toml::table>;
Node convert(py::handle v, const std::string& key, bool allowTables, const std::string& what);

void insert(toml::table& t, const std::string& name, Node node) {
    std::visit([&](auto&& x) { t.insert_or_assign(name, std::move(x)); }, std::move(node));
}

toml::table toTable(const py::dict& d, const std::string& prefix, const std::string& what) {
    toml::table t;
    for (const auto& [k, v] : d) {
        if (!py::isinstance<py::str>(k))
            throw MirageError(what + ": key " + std::string(py::repr(k)) + " under '" + prefix +
                              "' is not a str");
        const std::string name = py::str(k);
        insert(t, name, convert(v, prefix.empty() ? name : prefix + "." + name, true, what));
    }
    return t;
}

Node convert(py::handle v, const std::string& key, bool allowTables, const std::string& what) {
    if (numpyKind(v)) return convert(v.attr("item")(), key, allowTables, what);
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
    if (py::isinstance<py::int_>(v)) return v.cast<int64_t>();
    if (py::isinstance<py::float_>(v)) return v.cast<double>();
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    if (allowTables && py::isinstance<py::dict>(v))
        return toTable(py::reinterpret_borrow<py::dict>(v), key, what);
    if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
        toml::array a;
        size_t i = 0;
        for (py::handle e : v)
            std::visit([&](auto&& x) { a.push_back(std::move(x)); },
                       convert(e, key + "." + std::to_string(i++), allowTables, what));
        return a;
    }
    refuse(what, key, v);
}

}  // namespace

std::string sceneToml(const py::dict& scene) {
    std::ostringstream text;
    // Never empty: an empty text would mean "read the file" (frame/frame_request.h).
    text << "# a scene built in code (mirage.Scene.from_dict)\n";
    text << toml::toml_formatter(toTable(scene, "", "scene dict"));
    return text.str();
}

std::vector<std::string> overrideAssignments(const py::dict& set) {
    std::vector<std::string> out;
    for (const auto& [k, v] : set) {
        const std::string key = py::str(k);
        toml::table one;
        insert(one, "v", convert(v, key, false, "set"));
        std::ostringstream text;
        text << toml::toml_formatter(one);
        std::string value = text.str();  // "v = <value>"
        value = value.substr(value.find('=') + 2);
        while (!value.empty() && std::isspace(static_cast<unsigned char>(value.back())))
            value.pop_back();
        out.push_back(key + "=" + value);
    }
    return out;
}

}  // namespace mirage::python
