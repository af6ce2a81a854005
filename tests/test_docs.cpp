// The docs against the code: the macro reference generated from the macro specs, the
// paths the docs name, and code the docs quote.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <vector>

#include "macros/macro_table.hpp"
#include "tirefe/test_paths.hpp"

namespace {

namespace fs = std::filesystem;

std::string file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// A file of the repository, which must exist.
std::string source_text(const std::string& relative) {
  const fs::path path = fs::path(TIREFE_SOURCE_DIR) / relative;
  REQUIRE(fs::exists(path));
  return file_text(path);
}

}  // namespace

// Regenerate the pages with: bash scripts/macro-reference.sh
TEST_CASE("docs/macros.md and the pages it lists are the current macro reference", "[docs]") {
  const std::string reference = tirefe::macros::macro_reference();
  const size_t first_section = reference.find("\n## ");
  REQUIRE(first_section != std::string::npos);
  // The index opens with the reference's preamble and lists the pages in order; each page
  // is a title line of its own followed by the reference's sections, verbatim.
  const std::string index = source_text("docs/macros.md");
  CHECK(index.rfind(reference.substr(0, first_section) + "\n", 0) == 0);
  const std::regex page_name(R"(docs/macros_\w+\.md)");
  std::string sections;
  int pages = 0;
  for (std::sregex_iterator page(index.begin(), index.end(), page_name), end; page != end; ++page, ++pages) {
    const std::string text = source_text(page->str());
    INFO(page->str());
    CHECK(std::count(text.begin(), text.end(), '\n') <= 400);
    const size_t start = text.find("\n## ");
    REQUIRE(start != std::string::npos);
    sections += text.substr(start);
    // The index names every macro of the page.
    const std::regex macro_heading(R"(\n## (tirefe\.|model:)(\w+)\n)");
    for (std::sregex_iterator macro(text.begin(), text.end(), macro_heading); macro != end; ++macro) {
      INFO("macro " << (*macro)[0]);
      const std::string name = (*macro)[2], full = (*macro)[1].str() + name;
      CHECK((index.find("`" + name + "`") != std::string::npos || index.find("`" + full + "`") != std::string::npos));
    }
  }
  CHECK(pages == 4);
  CHECK(sections == reference.substr(first_section));
}

namespace {

// The repository's text files: sources, decks, scripts, docs, data. Build folders (those
// holding a CMakeCache.txt) and hidden folders are not the repository's.
std::vector<fs::path> repository_text_files() {
  const std::vector<std::string> extensions = {".md", ".cpp", ".hpp", ".lua", ".py", ".sh", ".txt", ".csv", ".tir"};
  std::vector<fs::path> files;
  const fs::path root(TIREFE_SOURCE_DIR);
  for (auto entry = fs::recursive_directory_iterator(root); entry != fs::recursive_directory_iterator(); ++entry) {
    const fs::path& path = entry->path();
    if (entry->is_directory()) {
      if (path.filename().string().front() == '.' || fs::exists(path / "CMakeCache.txt"))
        entry.disable_recursion_pending();
      continue;
    }
    const std::string extension = path.extension().string();
    if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) files.push_back(path);
  }
  return files;
}

}  // namespace

TEST_CASE("no file of the repository names a document outside it", "[docs]") {
  // Spelt in pieces so that this file does not name them itself.
  const std::vector<std::string> outside = {std::string("..") + "/shared", std::string("shared") + "/docs",
                                            std::string("MODEL") + ".md",  std::string("TIRE-") + "DATA",
                                            std::string("STYLE") + ".md",  std::string("PERFORMANCE") + ".md"};
  const std::vector<fs::path> files = repository_text_files();
  CHECK(files.size() > 100);
  for (const fs::path& path : files) {
    const std::string text = file_text(path);
    for (const std::string& name : outside) {
      INFO(path.string() << " names " << name << ": point at docs/model.md or docs/tire_data.md instead");
      CHECK(text.find(name) == std::string::npos);
    }
  }
}

TEST_CASE("every repository path that the docs and the README name exists", "[docs]") {
  // docs/NAME.md, inputs/..., post/NAME.py, scripts/NAME.sh, src/..., lua/..., tests/...,
  // bench/... not preceded by another path part (build/bench_x, results/x are outputs).
  const std::regex mention(R"((^|[^\w/.-])((docs|inputs|post|scripts|src|lua|tests|bench)/[\w/.-]*\w/?))");
  const fs::path root(TIREFE_SOURCE_DIR);
  std::vector<fs::path> documents = {root / "README.md"};
  for (const auto& entry : fs::directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md") documents.push_back(entry.path());
  int mentions = 0;
  for (const fs::path& document : documents) {
    std::ifstream in(document);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
      for (std::sregex_iterator match(line.begin(), line.end(), mention), end; match != end; ++match) {
        const std::string named = (*match)[2];
        INFO(document.string() << ":" << number << " names " << named << ", which is not in the repository");
        CHECK(fs::exists(root / named));
        ++mentions;
      }
    }
  }
  CHECK(mentions > 100);
}

// A fenced block whose info string says "source=PATH" quotes a file of the repository
// that the suite builds and runs (examples/): the quote must be that file, verbatim.
// Returns how many blocks 'doc' quotes.
static int check_quoted_sources(const std::string& doc) {
  std::ifstream in(std::string(TIREFE_SOURCE_DIR) + "/" + doc);
  REQUIRE(in.good());
  int quoted = 0;
  std::string line, source, text;
  bool inside = false;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("```", 0) != 0) {
      if (inside) text += line + "\n";
      continue;
    }
    inside = !inside;
    if (inside) {
      const size_t at = line.find("source=");
      source = at == std::string::npos ? "" : line.substr(at + 7);
      text.clear();
    } else if (!source.empty()) {
      std::ifstream file(std::string(TIREFE_SOURCE_DIR) + "/" + source);
      INFO(doc << " quotes " << source << " (block ending at line " << number << ")");
      REQUIRE(file.good());
      CHECK(text == std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>()));
      ++quoted;
    }
  }
  return quoted;
}

TEST_CASE("code quoted in docs/coupling.md, docs/fmu.md and docs/python.md is the built and tested file", "[docs]") {
  CHECK(check_quoted_sources("docs/coupling.md") == 2);  // the consumer project, the C quarter car
  CHECK(check_quoted_sources("docs/fmu.md") == 1);       // the FMU's check
  CHECK(check_quoted_sources("docs/python.md") == 2);    // the Python quarter car, the k_sw fit
}

TEST_CASE("the C++ host quoted in docs/spindle.md is the built and tested file", "[docs]") {
  CHECK(check_quoted_sources("docs/spindle.md") == 1);  // examples/spindle_host.cpp
}

TEST_CASE("the worked examples quoted in docs/extending.md are the built and tested files", "[docs]") {
  CHECK(check_quoted_sources("docs/extending.md") == 5);  // examples/extending/: element, surface, macro, deck, output
}

TEST_CASE("the deck docs/first_deck.md reads is the shipped one", "[docs]") {
  CHECK(check_quoted_sources("docs/first_deck.md") == 1);  // inputs/cantilever_elastica.lua
}

TEST_CASE("docs/README.md, the index of the docs, names every page", "[docs]") {
  const std::string index = source_text("docs/README.md");
  int pages = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(TIREFE_SOURCE_DIR) / "docs")) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".md" || name == "README.md") continue;
    INFO("docs/" << name << " is not in docs/README.md");
    CHECK(index.find("docs/" + name) != std::string::npos);
    ++pages;
  }
  CHECK(pages > 20);
}
