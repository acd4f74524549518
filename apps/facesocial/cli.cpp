#include "cli.hpp"

#include <cmath>
#include <cstdio>

namespace facesocial::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.rfind("--", 0) == 0 && a.size() > 2) {
            std::string name = a, value;
            const auto eq = a.find('=');
            const bool inline_value = eq != std::string::npos;
            if (inline_value) name = a.substr(0, eq), value = a.substr(eq + 1);
            if (valued.count(name)) {
                if (!inline_value) {
                    if (i + 1 >= argv.size()) throw UsageError("option " + name + " needs a value");
                    value = argv[++i];
                }
                values_[name] = value;
            } else if (flags.count(name) && !inline_value) {
                flags_.insert(name);
            } else {
                throw UsageError("unknown option " + a);
            }
        } else {
            positional_.push_back(a);
        }
    }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
    auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
}

int Args::get_int(const std::string& name, int fallback) const {
    if (!has(name)) return fallback;
    const std::string v = get(name);
    try {
        std::size_t used = 0;
        const int i = std::stoi(v, &used);
        if (used == v.size()) return i;
    } catch (const std::exception&) {
    }
    throw UsageError("option " + name + ": expected an integer, got '" + v + "'");
}

double Args::get_double(const std::string& name, double fallback) const {
    if (!has(name)) return fallback;
    const std::string v = get(name);
    try {
        std::size_t used = 0;
        const double d = std::stod(v, &used);
        if (used == v.size()) return d;
    } catch (const std::exception&) {
    }
    throw UsageError("option " + name + ": expected a number, got '" + v + "'");
}

std::string quote(const std::string& s) {
    std::string out = "\"";
    for (unsigned char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\r': out += "\\r"; break;
            case '\t': out += "\\t"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += char(c);
                }
        }
    }
    return out + "\"";
}

std::string number(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

JsonObject& JsonObject::add(const std::string& key, double value) { return raw(key, number(value)); }

JsonObject& JsonObject::add(const std::string& key, const std::vector<JsonObject>& values) {
    std::string s = "[";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i) s += ',';
        s += values[i].str();
    }
    s += ']';
    return raw(key, s);
}

JsonObject& JsonObject::add(const std::string& key, const std::vector<double>& values) {
    std::string s = "[";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i) s += ',';
        s += number(values[i]);
    }
    s += ']';
    return raw(key, s);
}

JsonObject& JsonObject::raw(const std::string& key, const std::string& json) {
    if (!first_) body_ += ",";
    first_ = false;
    body_ += quote(key) + ":" + json;
    return *this;
}

std::vector<ClassifierKind> parse_methods(const std::string& list) {
    std::vector<ClassifierKind> kinds;
    std::stringstream ss(list);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) {
            try {
                kinds.push_back(classifier_kind_from_string(item));
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("--methods: ") + e.what());
            }
        }
    if (kinds.empty()) throw UsageError("--methods: expected a comma-separated list of ehmm,eigen,fisher,lbph");
    return kinds;
}

}  // namespace facesocial::cli
