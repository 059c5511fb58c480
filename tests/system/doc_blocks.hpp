// The blocks of a Markdown walk-through the doc test runs, each with what it
// expects, read from an HTML comment on the line before its fence (invisible
// where the Markdown is rendered):
//
//   <!-- doc-test: skip (why it cannot run in CI) -->
//   <!-- doc-test: expect-exit=0 expect=/Ready/ stop-after=2 node=stopped -->
//
//   expect-exit=N or N,M,...  each command's exit code (one for all, or one a
//                             command, in order); default 0
//   expect=/REGEX/            the block's output (every command's stdout and
//                             stderr) has a match; may be given several times
//   stop-after=SECONDS        a command still running then gets Ctrl-C
//                             (SIGINT to its process group), as the docs say
//                             one stops it, and must then end with its exit
//                             code; without it a command must end by itself
//   node=running|stopped      the default node (jausd as ./scripts/run.sh
//                             starts it) runs during the block (default) or
//                             not (the block binds its port itself)
//   excerpt-of=PATH           (a yaml block) every line of the block is a line
//                             of PATH, without comments, in the same order
//   check-config              (a yaml block) `jausd --config <the block>
//                             --check-config` exits 0; expect= applies to it
//
// A paragraph after `<!-- doc-test: default-components -->` names the
// default node's components: every kind of config/jausd.yaml (underscores
// as spaces), and no other kind.
//
// Every `sh` block must be marked (a new one is thought about, not skipped
// unseen); other blocks run only when marked. A command is a line (with its
// `\` continuations); comment lines are left out.
#pragma once

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace jaus::test::docs {

struct DocBlock {
  std::string file;
  int line = 0;             // of the opening fence, 1-based
  std::string language;     // "sh", "yaml", "" ...
  std::vector<std::string> body;  // the lines between the fences
  bool marked = false;
  std::optional<std::string> skip;  // the reason
  std::vector<int> expect_exit{0};
  std::vector<std::string> expect;  // regexes
  std::optional<double> stop_after_s;
  bool node_running = true;
  std::optional<std::string> excerpt_of;
  bool check_config = false;
  std::string error;  // a marker that cannot be read: the test fails with it

  std::string where() const { return file + ":" + std::to_string(line); }
  // The commands of an sh block: continuation lines joined, blank and comment lines left out.
  std::vector<std::string> commands() const {
    std::vector<std::string> out;
    std::string pending;
    for (const auto& raw : body) {
      std::string l = raw;
      const auto first = l.find_first_not_of(" \t");
      if (pending.empty() && (first == std::string::npos || l[first] == '#')) continue;
      if (!l.empty() && l.back() == '\\') {
        pending += l.substr(0, l.size() - 1);
        continue;
      }
      out.push_back(pending + l);
      pending.clear();
    }
    if (!pending.empty()) out.push_back(pending);
    return out;
  }
};

struct Paragraph {
  std::string file;
  int line = 0;
  std::string text;  // its lines joined with spaces
};

struct ParsedDoc {
  std::vector<DocBlock> blocks;
  std::vector<Paragraph> default_component_lists;
  std::vector<std::string> errors;  // markers that cannot be read, fences not closed
};

namespace detail {

inline std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

// Fills `block` from the marker's text (after "doc-test:"); an error in block.error.
inline void read_marker(std::string text, DocBlock& block) {
  block.marked = true;
  text = trim(text);
  if (text.rfind("skip", 0) == 0) {
    const auto open = text.find('('), close = text.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close <= open + 1)
      block.error = "skip needs a reason in parentheses";
    else block.skip = text.substr(open + 1, close - open - 1);
    return;
  }
  std::size_t i = 0;
  bool exit_given = false;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ') ++i;
    if (i >= text.size()) break;
    const auto eq = text.find('=', i);
    const auto space = text.find(' ', i);
    std::string key = text.substr(i, std::min(eq, space) - i);
    if (eq == std::string::npos || (space != std::string::npos && space < eq)) {
      i = space == std::string::npos ? text.size() : space;
      if (key == "check-config") block.check_config = true;
      else block.error = "unknown doc-test directive '" + key + "'";
      continue;
    }
    std::string value;
    if (eq + 1 < text.size() && text[eq + 1] == '/') {
      // /REGEX/: up to a slash followed by a space or the end
      std::size_t end = eq + 2;
      while (end < text.size() && !(text[end] == '/' && (end + 1 == text.size() || text[end + 1] == ' '))) ++end;
      if (end >= text.size()) {
        block.error = "expect=/REGEX/ without its closing slash";
        return;
      }
      value = text.substr(eq + 2, end - eq - 2);
      i = end + 1;
    } else {
      const auto end = text.find(' ', eq + 1);
      value = text.substr(eq + 1, end == std::string::npos ? std::string::npos : end - eq - 1);
      i = end == std::string::npos ? text.size() : end;
    }
    try {
      if (key == "expect") block.expect.push_back(value);
      else if (key == "expect-exit") {
        if (!exit_given) block.expect_exit.clear();
        exit_given = true;
        std::istringstream codes(value);
        for (std::string code; std::getline(codes, code, ',');) block.expect_exit.push_back(std::stoi(code));
      } else if (key == "stop-after") block.stop_after_s = std::stod(value);
      else if (key == "node") {
        if (value != "running" && value != "stopped") block.error = "node=running or node=stopped, not " + value;
        block.node_running = value == "running";
      } else if (key == "excerpt-of") block.excerpt_of = value;
      else block.error = "unknown doc-test directive '" + key + "'";
    } catch (const std::exception&) {
      block.error = "doc-test directive " + key + ": '" + value + "' is not a number";
    }
  }
}

}  // namespace detail

inline ParsedDoc parse_doc(const std::string& file, std::istream& in) {
  ParsedDoc doc;
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::optional<std::string> marker;  // the marker of the next block or paragraph
  int marker_line = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string t = detail::trim(lines[i]);
    if (t.rfind("<!-- doc-test:", 0) == 0) {
      const auto end = t.find("-->");
      if (end == std::string::npos) {
        doc.errors.push_back(file + ":" + std::to_string(i + 1) + ": doc-test marker without -->");
        continue;
      }
      marker = t.substr(14, end - 14);
      marker_line = static_cast<int>(i + 1);
      continue;
    }
    if (t.empty()) continue;
    if (marker && detail::trim(*marker) == "default-components") {
      Paragraph p{file, static_cast<int>(i + 1), ""};
      for (; i < lines.size() && !detail::trim(lines[i]).empty(); ++i) p.text += " " + detail::trim(lines[i]);
      doc.default_component_lists.push_back(p);
      marker.reset();
      continue;
    }
    if (lines[i].rfind("```", 0) == 0) {
      DocBlock block;
      block.file = file;
      block.line = static_cast<int>(i + 1);
      block.language = detail::trim(lines[i].substr(3));
      std::size_t j = i + 1;
      for (; j < lines.size() && detail::trim(lines[j]) != "```"; ++j) block.body.push_back(lines[j]);
      if (j == lines.size()) doc.errors.push_back(block.where() + ": fence not closed");
      if (marker) detail::read_marker(*marker, block);
      if (!block.error.empty()) doc.errors.push_back(block.where() + ": " + block.error);
      doc.blocks.push_back(std::move(block));
      marker.reset();
      i = j;
      continue;
    }
    if (marker) {
      doc.errors.push_back(file + ":" + std::to_string(marker_line) + ": doc-test marker not right before a block");
      marker.reset();
    }
  }
  return doc;
}

inline ParsedDoc parse_doc_file(const std::string& path, const std::string& shown_as) {
  std::ifstream in(path);
  if (!in) {
    ParsedDoc doc;
    doc.errors.push_back(path + ": cannot open");
    return doc;
  }
  return parse_doc(shown_as, in);
}

}  // namespace jaus::test::docs
