// compare_generated COMMITTED FRESH REL ABS: exit 0 when FRESH says what COMMITTED says - the same
// text, and every number within max(REL x its size, ABS) of the committed one - else 1, printing
// the first differences with their line numbers. Generated documents are compared by what they
// claim, not byte for byte: a measured rounding error (1.2e-14 on one CPU, 2.1e-15 where glibc's
// libm dispatches to another variant) is the same claim; a verdict ("yes"/"no"), a word or a
// number beyond the tolerance is not.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

namespace {

struct Token {
  bool number = false;
  double value = 0.0;
  std::string text;
  int line = 1;
};

bool starts_number(const std::string& s, std::size_t i) {
  const auto digit = [&](std::size_t k) { return k < s.size() && s[k] >= '0' && s[k] <= '9'; };
  if (digit(i)) return true;
  if (s[i] == '.' && digit(i + 1)) return true;
  if ((s[i] == '-' || s[i] == '+') && (digit(i + 1) || (i + 2 < s.size() && s[i + 1] == '.' && digit(i + 2))))
    return i == 0 || !(std::isalnum(static_cast<unsigned char>(s[i - 1])));  // "a-1" stays a word
  return false;
}

std::vector<Token> tokens(const std::string& s) {
  std::vector<Token> out;
  int line = 1;
  for (std::size_t i = 0; i < s.size();) {
    const bool in_word = i > 0 && (std::isalpha(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '_');
    if (!in_word && starts_number(s, i)) {
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(s.c_str() + i, &end);
      const std::size_t n = static_cast<std::size_t>(end - (s.c_str() + i));
      if (n > 0 && errno == 0) {
        out.push_back({true, v, s.substr(i, n), line});
        i += n;
        continue;
      }
    }
    if (s[i] == '\n') ++line;
    out.push_back({false, 0.0, std::string(1, s[i]), line});
    ++i;
  }
  return out;
}

std::string slurp(const char* path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    std::cerr << "cannot read " << path << "\n";
    std::exit(2);
  }
  return std::string(std::istreambuf_iterator<char>(f), {});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::cerr << "usage: compare_generated COMMITTED FRESH REL ABS\n";
    return 2;
  }
  const double rel = std::strtod(argv[3], nullptr), abs_tol = std::strtod(argv[4], nullptr);
  const std::vector<Token> a = tokens(slurp(argv[1])), b = tokens(slurp(argv[2]));
  int shown = 0;
  const auto differ = [&](const Token& x, const Token& y, const char* why) {
    if (shown++ < 10)
      std::cout << "line " << x.line << " (fresh line " << y.line << "): committed '" << x.text << "', fresh '" << y.text
                << "' (" << why << ")\n";
  };
  std::size_t i = 0;
  for (; i < a.size() && i < b.size(); ++i) {
    const Token &x = a[i], &y = b[i];
    if (x.number != y.number) {
      differ(x, y, "a number against text");
      break;  // the rest is out of step
    }
    if (!x.number) {
      if (x.text != y.text) differ(x, y, "text");
      continue;
    }
    const double scale = std::max(std::abs(x.value), std::abs(y.value));
    if (!(std::abs(x.value - y.value) <= std::max(rel * scale, abs_tol)) && !(x.value == y.value))
      differ(x, y, "beyond the tolerance");
  }
  if (shown == 0 && a.size() != b.size()) {
    std::cout << "the files differ in length: " << a.size() << " and " << b.size() << " tokens\n";
    ++shown;
  }
  if (shown > 0) std::cout << shown << " difference(s); tolerance: relative " << rel << ", absolute " << abs_tol << "\n";
  return shown > 0 ? 1 : 0;
}
