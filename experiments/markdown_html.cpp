#include <refract/experiments/markdown_html.h>

#include <cctype>
#include <sstream>
#include <vector>

#include <refract/validation/files.h>

namespace refract::experiments {

using validation::html_escape;

namespace {

bool relative_target(const std::string& t) {
    if (t.empty() || t[0] == '/' || t[0] == '#') return false;
    for (char c : t) {
        if (c == ':') return false;  // a scheme (http:, mailto:, ...)
        if (c == '/' || c == '?' || c == '#') break;
    }
    return true;
}

std::string target(const std::string& t, const std::string& base) {
    return html_escape(relative_target(t) ? url_path(base + t) : t);
}

// Inline spans of one block's text.
std::string inline_html(const std::string& s, const std::string& base) {
    std::string o;
    size_t i = 0;
    auto closing = [&s](size_t from, const std::string& mark) { return s.find(mark, from); };
    while (i < s.size()) {
        const char c = s[i];
        if (c == '`') {
            const size_t e = closing(i + 1, "`");
            if (e != std::string::npos) {
                o += "<code>" + html_escape(s.substr(i + 1, e - i - 1)) + "</code>";
                i = e + 1;
                continue;
            }
        }
        if (s.compare(i, 2, "**") == 0) {
            const size_t e = closing(i + 2, "**");
            if (e != std::string::npos && e > i + 2) {
                o += "<strong>" + inline_html(s.substr(i + 2, e - i - 2), base) + "</strong>";
                i = e + 2;
                continue;
            }
        }
        if (c == '*' && i + 1 < s.size() && !std::isspace(static_cast<unsigned char>(s[i + 1]))) {
            const size_t e = closing(i + 1, "*");
            if (e != std::string::npos && e > i + 1 && !std::isspace(static_cast<unsigned char>(s[e - 1]))) {
                o += "<em>" + inline_html(s.substr(i + 1, e - i - 1), base) + "</em>";
                i = e + 1;
                continue;
            }
        }
        const bool image = c == '!' && i + 1 < s.size() && s[i + 1] == '[';
        if (c == '[' || image) {
            const size_t open = i + (image ? 1 : 0), close = closing(open + 1, "]");
            if (close != std::string::npos && close + 1 < s.size() && s[close + 1] == '(') {
                const size_t end = closing(close + 2, ")");
                if (end != std::string::npos) {
                    const std::string text = s.substr(open + 1, close - open - 1);
                    const std::string href = target(s.substr(close + 2, end - close - 2), base);
                    if (image)
                        o += "<a href=\"" + href + "\"><img src=\"" + href + "\" alt=\"" + html_escape(text) + "\"></a>";
                    else
                        o += "<a href=\"" + href + "\">" + inline_html(text, base) + "</a>";
                    i = end + 1;
                    continue;
                }
            }
        }
        o += html_escape(std::string(1, c));
        ++i;
    }
    return o;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// The cells of a pipe-table row (outer pipes optional).
std::vector<std::string> cells(std::string row) {
    row = trim(row);
    if (!row.empty() && row.front() == '|') row.erase(0, 1);
    if (!row.empty() && row.back() == '|') row.pop_back();
    std::vector<std::string> v;
    std::string cell;
    bool code = false;
    for (char c : row) {
        if (c == '`') code = !code;
        if (c == '|' && !code) {
            v.push_back(trim(cell));
            cell.clear();
        } else {
            cell += c;
        }
    }
    v.push_back(trim(cell));
    return v;
}

bool separator_row(const std::string& line) {
    const std::string t = trim(line);
    if (t.empty() || t.find('-') == std::string::npos) return false;
    for (char c : t)
        if (c != '|' && c != '-' && c != ':' && c != ' ') return false;
    return true;
}

// "- x", "* x" -> 'u'; "12. x" -> 'o'; else 0. `rest` gets the item's text.
char list_item(const std::string& line, std::string& rest) {
    if (line.size() > 2 && (line[0] == '-' || line[0] == '*') && line[1] == ' ') {
        rest = line.substr(2);
        return 'u';
    }
    size_t k = 0;
    while (k < line.size() && std::isdigit(static_cast<unsigned char>(line[k]))) ++k;
    if (k > 0 && k + 1 < line.size() && line[k] == '.' && line[k + 1] == ' ') {
        rest = line.substr(k + 2);
        return 'o';
    }
    return 0;
}

std::string slug(const std::string& text) {
    std::string s;
    for (unsigned char c : text) {
        if (std::isalnum(c)) s += static_cast<char>(std::tolower(c));
        else if (!s.empty() && s.back() != '-') s += '-';
    }
    while (!s.empty() && s.back() == '-') s.pop_back();
    return s;
}

}  // namespace

std::string url_path(const std::string& path) {
    static const char* hex = "0123456789ABCDEF";
    std::string o;
    for (unsigned char c : path) {
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            o += static_cast<char>(c);
        } else {
            o += '%';
            o += hex[c >> 4];
            o += hex[c & 15];
        }
    }
    return o;
}

std::string markdown_to_html(const std::string& markdown, const std::string& base) {
    std::vector<std::string> lines;
    {
        std::istringstream in(markdown);
        std::string line;
        while (std::getline(in, line)) {
            if (!line.empty() && line.back() == '\r') line.pop_back();
            lines.push_back(line);
        }
    }
    std::ostringstream h;
    size_t i = 0;
    const size_t n = lines.size();
    while (i < n) {
        const std::string& line = lines[i];
        const std::string t = trim(line);
        std::string rest;
        if (t.empty()) {
            ++i;
        } else if (t.rfind("```", 0) == 0) {  // fenced code
            h << "<pre><code>";
            for (++i; i < n && trim(lines[i]).rfind("```", 0) != 0; ++i) h << html_escape(lines[i]) << "\n";
            h << "</code></pre>\n";
            ++i;
        } else if (t[0] == '#') {
            size_t level = 0;
            while (level < t.size() && t[level] == '#') ++level;
            if (level <= 6 && level < t.size() && t[level] == ' ') {
                const std::string text = trim(t.substr(level));
                h << "<h" << level << " id=\"" << slug(text) << "\">" << inline_html(text, base) << "</h" << level
                  << ">\n";
                ++i;
            } else {
                h << "<p>" << inline_html(t, base) << "</p>\n";
                ++i;
            }
        } else if (t[0] == '|' && i + 1 < n && separator_row(lines[i + 1])) {  // pipe table
            const auto head = cells(t);
            std::vector<std::string> align;
            for (const auto& c : cells(lines[i + 1])) {
                const bool left = !c.empty() && c.front() == ':', right = !c.empty() && c.back() == ':';
                align.push_back(left && right ? "center" : right ? "right" : left ? "left" : "");
            }
            auto style = [&align](size_t k) {
                return k < align.size() && !align[k].empty() ? " style=\"text-align:" + align[k] + "\"" : std::string();
            };
            h << "<div class=\"scroll\"><table>\n<thead><tr>";
            for (size_t k = 0; k < head.size(); ++k) h << "<th" << style(k) << ">" << inline_html(head[k], base) << "</th>";
            h << "</tr></thead>\n<tbody>\n";
            for (i += 2; i < n && !trim(lines[i]).empty() && trim(lines[i])[0] == '|'; ++i) {
                const auto row = cells(lines[i]);
                h << "<tr>";
                for (size_t k = 0; k < row.size(); ++k) h << "<td" << style(k) << ">" << inline_html(row[k], base) << "</td>";
                h << "</tr>\n";
            }
            h << "</tbody></table></div>\n";
        } else if (const char kind = list_item(t, rest)) {
            const char* tag = kind == 'u' ? "ul" : "ol";
            h << "<" << tag << ">\n";
            while (i < n) {
                std::string item;
                if (list_item(trim(lines[i]), item) != kind) break;
                // Continuation lines: indented, not a new item, not blank.
                for (++i; i < n && !trim(lines[i]).empty() && (lines[i][0] == ' ' || lines[i][0] == '\t'); ++i) {
                    std::string dummy;
                    if (list_item(trim(lines[i]), dummy)) break;
                    item += " " + trim(lines[i]);
                }
                h << "<li>" << inline_html(item, base) << "</li>\n";
            }
            h << "</" << tag << ">\n";
        } else {  // a paragraph: lines up to a blank line or another block's start
            std::string para = t;
            for (++i; i < n; ++i) {
                const std::string u = trim(lines[i]);
                std::string dummy;
                if (u.empty() || u[0] == '#' || u[0] == '|' || u.rfind("```", 0) == 0 || list_item(u, dummy)) break;
                para += "\n" + u;
            }
            h << "<p>" << inline_html(para, base) << "</p>\n";
        }
    }
    return h.str();
}

}  // namespace refract::experiments
