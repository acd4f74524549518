#include "facesocial/datasets.hpp"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"
#include "parallel.hpp"

namespace facesocial {

namespace fs = std::filesystem;

fs::path data_root() {
    const char* env = std::getenv("FACESOCIAL_DATA");
    if (!env || !*env)
        throw FileError("$FACESOCIAL_DATA", "is not set; point it at the face sets (see datasets/README)");
    std::error_code ec;
    if (!fs::is_directory(env, ec)) throw FileError(env, "($FACESOCIAL_DATA) is not a directory");
    return fs::absolute(env);
}

namespace {

std::string attribute(const std::string& tag, const std::string& name, const fs::path& xml) {
    const std::regex re(name + R"(\s*=\s*['"]([^'"]*)['"])");
    std::smatch m;
    if (!std::regex_search(tag, m, re))
        throw ModelFormatError(xml.string(), "malformed imglab XML: attribute '" + name + "' missing in " + tag);
    return m[1];
}

int int_attribute(const std::string& tag, const std::string& name, const fs::path& xml) {
    const std::string v = attribute(tag, name, xml);
    try {
        std::size_t used = 0;
        const int i = std::stoi(v, &used);
        if (used == v.size()) return i;
    } catch (const std::exception&) {
    }
    throw ModelFormatError(xml.string(), "malformed imglab XML: expected an integer " + name + ", got '" + v + "'");
}

}  // namespace

std::vector<AnnotatedImage> load_imglab_xml(const fs::path& xml) {
    std::ifstream in(xml);
    if (!in) throw FileError(xml.string(), "cannot be opened for reading");
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    if (text.find("<images>") == std::string::npos)
        throw ModelFormatError(xml.string(), "is not a dlib imglab dataset (no <images> element)");

    std::vector<AnnotatedImage> out;
    const std::regex image_re(R"(<image\s[^>]*>([\s\S]*?)</image>)");
    const std::regex box_re(R"(<box\s[^>]*>)");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), image_re); it != std::sregex_iterator(); ++it) {
        const std::string whole = (*it)[0];
        const std::string open_tag = whole.substr(0, whole.find('>') + 1);
        AnnotatedImage image;
        image.file = xml.parent_path() / attribute(open_tag, "file", xml);
        const std::string body = (*it)[1];
        for (auto b = std::sregex_iterator(body.begin(), body.end(), box_re); b != std::sregex_iterator(); ++b) {
            const std::string tag = (*b)[0];
            if (tag.find("ignore='1'") != std::string::npos) continue;
            image.faces.emplace_back(int_attribute(tag, "left", xml), int_attribute(tag, "top", xml),
                                     int_attribute(tag, "width", xml), int_attribute(tag, "height", xml));
        }
        out.push_back(std::move(image));
    }
    return out;
}

std::vector<AnnotatedImage> load_dlib_faces(const fs::path& root) {
    std::vector<AnnotatedImage> all = load_imglab_xml(root / "dlib_faces" / "training.xml");
    std::vector<AnnotatedImage> test = load_imglab_xml(root / "dlib_faces" / "testing.xml");
    all.insert(all.end(), test.begin(), test.end());
    return all;
}

std::vector<PersonImages> load_identity_folders(const fs::path& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw FileError(folder.string(), "is not a directory");
    std::vector<PersonImages> people;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (!entry.is_directory()) continue;
        PersonImages p{entry.path().filename().string(), list_images(entry.path())};
        if (!p.images.empty()) people.push_back(std::move(p));
    }
    if (people.empty())
        throw FileError(folder.string(), "holds no sub-folder with images (expected one folder of images per person)");
    std::sort(people.begin(), people.end(),
              [](const PersonImages& a, const PersonImages& b) { return natural_less(a.name, b.name); });
    return people;
}

bool natural_less(const std::string& a, const std::string& b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (std::isdigit((unsigned char)a[i]) && std::isdigit((unsigned char)b[j])) {
            std::size_t i2 = i, j2 = j;
            while (i2 < a.size() && std::isdigit((unsigned char)a[i2])) ++i2;
            while (j2 < b.size() && std::isdigit((unsigned char)b[j2])) ++j2;
            std::string na = a.substr(i, i2 - i), nb = b.substr(j, j2 - j);
            na.erase(0, std::min(na.find_first_not_of('0'), na.size()));
            nb.erase(0, std::min(nb.find_first_not_of('0'), nb.size()));
            if (na.size() != nb.size()) return na.size() < nb.size();
            if (na != nb) return na < nb;
            i = i2, j = j2;
        } else {
            if (a[i] != b[j]) return a[i] < b[j];
            ++i, ++j;
        }
    }
    return a.size() - i < b.size() - j;
}

FaceSet load_cropped_faces(const std::filesystem::path& folder, const NormalizerParams& params) {
    const FaceNormalizer normalizer(params);
    const auto people = load_identity_folders(folder);
    FaceSet set;
    for (const auto& p : people) {
        set.names.push_back(p.name);
        set.faces.emplace_back(p.images.size());
    }
    std::vector<std::pair<std::size_t, std::size_t>> jobs;
    for (std::size_t p = 0; p < people.size(); ++p)
        for (std::size_t i = 0; i < people[p].images.size(); ++i) jobs.emplace_back(p, i);
    detail::parallel_for(jobs.size(), [&](std::size_t j) {
        const auto [p, i] = jobs[j];
        set.faces[p][i] = normalizer.normalize(load_image(people[p].images[i], ImageColor::Grey)).pixels;
    });
    return set;
}

}  // namespace facesocial
