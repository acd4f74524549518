// Command-line plumbing shared by the facesocial subcommands: argument parsing and JSON output.
#pragma once

#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "facesocial/face_classifier.hpp"

namespace facesocial::cli {

/// A usage mistake on the command line (exit code 2).
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Parsed command line of one subcommand.
class Args {
public:
    /// `valued` lists the options that take a value ("--out"), `flags` the boolean ones
    /// ("--json"). Anything else starting with "--" is a UsageError.
    Args(const std::vector<std::string>& argv, const std::set<std::string>& valued,
         const std::set<std::string>& flags);

    bool flag(const std::string& name) const { return flags_.count(name) > 0; }
    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::string get(const std::string& name, const std::string& fallback = "") const;
    int get_int(const std::string& name, int fallback) const;
    double get_double(const std::string& name, double fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }

private:
    std::map<std::string, std::string> values_;
    std::set<std::string> flags_;
    std::vector<std::string> positional_;
};

/// JSON string literal with escapes.
std::string quote(const std::string& s);

/// Builds one JSON object with keys in insertion order.
class JsonObject {
public:
    JsonObject& add(const std::string& key, const std::string& value) { return raw(key, quote(value)); }
    JsonObject& add(const std::string& key, const char* value) { return raw(key, quote(value)); }
    JsonObject& add(const std::string& key, double value);
    JsonObject& add(const std::string& key, int value) { return raw(key, std::to_string(value)); }
    JsonObject& add(const std::string& key, long value) { return raw(key, std::to_string(value)); }
    JsonObject& add(const std::string& key, std::size_t value) { return raw(key, std::to_string(value)); }
    JsonObject& add(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
    JsonObject& add(const std::string& key, const JsonObject& value) { return raw(key, value.str()); }
    JsonObject& add(const std::string& key, const std::vector<JsonObject>& values);
    JsonObject& add(const std::string& key, const std::vector<double>& values);
    /// Adds an already formatted JSON value.
    JsonObject& raw(const std::string& key, const std::string& json);
    std::string str() const { return "{" + body_ + "}"; }

private:
    std::string body_;
    bool first_ = true;
};

/// Parses --methods: a comma-separated list of ehmm, eigen, fisher, lbph.
std::vector<ClassifierKind> parse_methods(const std::string& list);

/// Formats a number for JSON (finite: shortest round-trip form; otherwise null).
std::string number(double v);

}  // namespace facesocial::cli
