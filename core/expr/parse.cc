// Parse: hand-written recursive-descent parser for Tcl-expr-like text.
//
// Design.  A small lexer produces one token at a time (with its byte offset);
// the parser has one function per precedence level, lowest first, matching
// Tcl 8.6's expr (the infix levels from or to relation are one function that
// reads the operators and their precedence from the operator table, ops.h, as
// do function calls):
//   ternary  := or ('?' ternary ':' ternary)?          right associative
//   or       := and ('||' and)*
//   and      := equality ('&&' equality)*
//   equality := relation (('==' | '!=') relation)*
//   relation := additive (('<' | '<=' | '>' | '>=') additive)*
//   additive := multiplicative (('+' | '-') multiplicative)*
//   multiplicative := power (('*' | '/' | '%') power)*
//   power    := unary ('**' power)?                     right associative
//   unary    := ('-' | '+' | '!') unary | primary
//   primary  := number | name | function '(' args ')' | '(' ternary ')'
// As in Tcl, unary operators bind tighter than **: -2**2 is 4 and 2**-2**2 is
// 16.  % follows Tcl (the result has the sign of the divisor).  Numbers are
// doubles (Tcl's integer division is not modelled: 7/2 is 3.5).  Additive and
// multiplicative chains are collected and built with one Sum / Product call,
// so long chains cost O(n log n).
//
// Robustness: every error is a ParseError with the byte offset of the
// offending token; nesting (parentheses, calls, ?:, unary operators and **
// chains) is limited to kMaxDepth levels so no input can exhaust the stack.
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "core/expr/expr.h"
#include "core/expr/ops.h"

namespace asgard::expr {
namespace {

constexpr int kMaxDepth = 200;

enum class Tok {
  kEnd,
  kNumber,
  kName,
  kOperator,  // an infix or prefix operation of the operator table (Token::op)
  kLParen,
  kRParen,
  kComma,
  kPlus,
  kMinus,
  kStar,
  kSlash,
  kPercent,
  kPower,
  kQuestion,
  kColon,
};

struct Token {
  Tok kind = Tok::kEnd;
  int offset = 0;
  std::string_view text;
  double number = 0.0;
  Op op = Op::kConst;  // kOperator
};

// Symbols that are not an operation of their own: arithmetic (a - b, a / b
// and a % b are built from sums, products and powers) and punctuation.
struct Symbol {
  std::string_view text;
  Tok kind;
};

constexpr Symbol kSymbols[] = {
    {"(", Tok::kLParen},  {")", Tok::kRParen},   {",", Tok::kComma},  {"+", Tok::kPlus},
    {"-", Tok::kMinus},   {"*", Tok::kStar},     {"**", Tok::kPower}, {"/", Tok::kSlash},
    {"%", Tok::kPercent}, {"?", Tok::kQuestion}, {":", Tok::kColon},
};

// What a character that starts no symbol was probably meant to be.
constexpr std::pair<char, const char*> kHints[] = {
    {'=', " (use == to compare)"},
    {'&', " (use &&)"},
    {'|', " (use ||)"},
};

bool IsOperatorSymbol(const OpInfo& info) {
  return info.notation == Notation::kInfix || info.notation == Notation::kPrefix;
}

bool IsIdentStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsIdentChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }

std::string Describe(std::string_view text, int offset) {
  const unsigned char c = static_cast<unsigned char>(text[offset]);
  if (std::isprint(c)) return std::string("'") + static_cast<char>(c) + "'";
  static const char kHex[] = "0123456789abcdef";
  return std::string("byte 0x") + kHex[c >> 4] + kHex[c & 15];
}

class Parser {
 public:
  Parser(std::string_view text, Pool& pool, const Resolver& resolve)
      : text_(text), pool_(pool), resolve_(resolve) {}

  NodeId ParseAll() {
    Advance();
    if (tok_.kind == Tok::kEnd) throw ParseError("empty expression", 0);
    const NodeId result = Ternary();
    if (tok_.kind != Tok::kEnd) Unexpected();
    return result;
  }

 private:
  class DepthGuard {
   public:
    DepthGuard(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxDepth)
        throw ParseError("expression nested too deeply (limit " + std::to_string(kMaxDepth) + ")",
                         p_.tok_.offset);
    }
    ~DepthGuard() { --p_.depth_; }
    DepthGuard(const DepthGuard&) = delete;
    DepthGuard& operator=(const DepthGuard&) = delete;

   private:
    Parser& p_;
  };

  // ---- lexer ----
  void Advance() {
    size_t i = pos_;
    while (i < text_.size() && (text_[i] == ' ' || text_[i] == '\t' || text_[i] == '\n' ||
                                text_[i] == '\r' || text_[i] == '\f' || text_[i] == '\v'))
      ++i;
    tok_ = Token{};
    tok_.offset = static_cast<int>(i);
    if (i >= text_.size()) {
      pos_ = i;
      tok_.kind = Tok::kEnd;
      return;
    }
    const char c = text_[i];
    const char next = i + 1 < text_.size() ? text_[i + 1] : '\0';
    size_t len = 1;
    if (IsDigit(c) || (c == '.' && IsDigit(next))) {
      len = LexNumber(i);
    } else if (IsIdentStart(c)) {
      size_t j = i + 1;
      while (j < text_.size() && IsIdentChar(text_[j])) ++j;
      while (j + 1 < text_.size() && text_[j] == '.' && IsIdentChar(text_[j + 1])) {
        j += 2;
        while (j < text_.size() && IsIdentChar(text_[j])) ++j;
      }
      tok_.kind = Tok::kName;
      len = j - i;
    } else {
      len = LexSymbol(i);
    }
    tok_.text = text_.substr(i, len);
    pos_ = i + len;
  }

  // Lexes the longest operator or punctuation symbol starting at i; returns
  // its length.
  size_t LexSymbol(size_t i) {
    const std::string_view rest = text_.substr(i);
    size_t len = 0;
    for (const Symbol& s : kSymbols) {
      if (s.text.size() > len && rest.starts_with(s.text)) {
        len = s.text.size();
        tok_.kind = s.kind;
      }
    }
    for (const OpInfo& info : kOps) {
      const std::string_view name = info.name;
      if (IsOperatorSymbol(info) && name.size() > len && rest.starts_with(name)) {
        len = name.size();
        tok_.kind = Tok::kOperator;
        tok_.op = info.op;
      }
    }
    if (len > 0) return len;
    std::string hint;
    for (const auto& [c, text] : kHints)
      if (rest[0] == c) hint = text;
    throw ParseError("unexpected character " + Describe(text_, tok_.offset) + hint, tok_.offset);
  }

  // Lexes the number starting at i; returns its length.
  size_t LexNumber(size_t i) {
    size_t j = i;
    while (j < text_.size() && IsDigit(text_[j])) ++j;
    if (j < text_.size() && text_[j] == '.') {
      ++j;
      while (j < text_.size() && IsDigit(text_[j])) ++j;
    }
    if (j < text_.size() && (text_[j] == 'e' || text_[j] == 'E')) {
      size_t k = j + 1;
      if (k < text_.size() && (text_[k] == '+' || text_[k] == '-')) ++k;
      if (k < text_.size() && IsDigit(text_[k])) {
        while (k < text_.size() && IsDigit(text_[k])) ++k;
        j = k;
      }
    }
    if (j < text_.size() && (IsIdentChar(text_[j]) || text_[j] == '.')) {
      size_t k = j;
      while (k < text_.size() && (IsIdentChar(text_[k]) || text_[k] == '.')) ++k;
      throw ParseError("malformed number '" + std::string(text_.substr(i, k - i)) + "'",
                       static_cast<int>(i));
    }
    const std::string_view s = text_.substr(i, j - i);
    double v = 0.0;
    auto res = std::from_chars(s.data(), s.data() + s.size(), v);
    if (res.ec == std::errc::result_out_of_range) {
      // Overflow gives infinity, underflow zero.
      const size_t e = s.find_first_of("eE");
      v = (e != std::string_view::npos && e + 1 < s.size() && s[e + 1] == '-') ? 0.0 : HUGE_VAL;
    } else if (res.ec != std::errc() || res.ptr != s.data() + s.size()) {
      throw ParseError("malformed number '" + std::string(s) + "'", static_cast<int>(i));
    }
    tok_.kind = Tok::kNumber;
    tok_.number = v;
    return j - i;
  }

  [[noreturn]] void Unexpected() {
    if (tok_.kind == Tok::kEnd) throw ParseError("unexpected end of expression", tok_.offset);
    throw ParseError("unexpected '" + std::string(tok_.text) + "'", tok_.offset);
  }

  void Expect(Tok kind, const char* what) {
    if (tok_.kind != kind) {
      if (tok_.kind == Tok::kEnd)
        throw ParseError(std::string("expected ") + what + " but reached the end of the expression",
                         tok_.offset);
      throw ParseError(std::string("expected ") + what + " before '" + std::string(tok_.text) + "'",
                       tok_.offset);
    }
    Advance();
  }

  NodeId Binary(Op op, NodeId a, NodeId b) { return pool_.Apply(op, std::array<NodeId, 2>{a, b}); }

  // ---- grammar ----
  NodeId Ternary() {
    DepthGuard guard(*this);
    const NodeId cond = Infix(kOrPrec);
    if (tok_.kind != Tok::kQuestion) return cond;
    Advance();
    const NodeId a = Ternary();
    Expect(Tok::kColon, "':'");
    const NodeId b = Ternary();
    return pool_.Select(cond, a, b);
  }

  // Left-associative infix operations of the operator table at precedence
  // `prec` (kOrPrec up to kRelational) over the levels above.
  NodeId Infix(int prec) {
    if (prec >= kAdditive) return Additive();
    NodeId lhs = Infix(prec + 1);
    while (tok_.kind == Tok::kOperator && Info(tok_.op).notation == Notation::kInfix &&
           Info(tok_.op).prec == prec) {
      const Op op = tok_.op;
      Advance();
      lhs = Binary(op, lhs, Infix(prec + 1));
    }
    return lhs;
  }

  NodeId Additive() {
    std::vector<NodeId> terms{Multiplicative()};
    while (tok_.kind == Tok::kPlus || tok_.kind == Tok::kMinus) {
      const bool minus = tok_.kind == Tok::kMinus;
      Advance();
      const NodeId term = Multiplicative();
      terms.push_back(minus ? pool_.Neg(term) : term);
    }
    return terms.size() == 1 ? terms[0] : pool_.Sum(terms);
  }

  NodeId Multiplicative() {
    std::vector<NodeId> factors{Power()};
    while (tok_.kind == Tok::kStar || tok_.kind == Tok::kSlash || tok_.kind == Tok::kPercent) {
      const Tok kind = tok_.kind;
      Advance();
      const NodeId rhs = Power();
      if (kind != Tok::kPercent && factors.size() == 1 && pool_.IsConst(factors[0]) &&
          pool_.IsConst(rhs)) {  // fold constant chains left to right (exact division)
        factors[0] = kind == Tok::kStar ? pool_.Mul(factors[0], rhs) : pool_.Div(factors[0], rhs);
      } else if (kind == Tok::kStar) {
        factors.push_back(rhs);
      } else if (kind == Tok::kSlash) {
        factors.push_back(pool_.Pow(rhs, pool_.Const(-1.0)));
      } else {  // % applies to the product so far
        const NodeId lhs = factors.size() == 1 ? factors[0] : pool_.Product(factors);
        factors.assign(1, pool_.Mod(lhs, rhs));
      }
    }
    return factors.size() == 1 ? factors[0] : pool_.Product(factors);
  }

  NodeId Power() {
    const NodeId base = Unary();
    if (tok_.kind != Tok::kPower) return base;
    DepthGuard guard(*this);
    Advance();
    return pool_.Pow(base, Power());
  }

  NodeId Unary() {
    switch (tok_.kind) {
      case Tok::kMinus: {
        DepthGuard guard(*this);
        Advance();
        return pool_.Neg(Unary());
      }
      case Tok::kPlus: {
        DepthGuard guard(*this);
        Advance();
        return Unary();
      }
      case Tok::kOperator: {
        if (Info(tok_.op).notation != Notation::kPrefix) return Primary();
        DepthGuard guard(*this);
        const Op op = tok_.op;
        Advance();
        return pool_.Apply(op, std::array<NodeId, 1>{Unary()});
      }
      default:
        return Primary();
    }
  }

  NodeId Primary() {
    switch (tok_.kind) {
      case Tok::kNumber: {
        const double v = tok_.number;
        Advance();
        return pool_.Const(v);
      }
      case Tok::kLParen: {
        Advance();
        const NodeId inner = Ternary();
        Expect(Tok::kRParen, "')'");
        return inner;
      }
      case Tok::kName:
        return Name();
      default:
        Unexpected();
    }
  }

  NodeId Name() {
    const Token name = tok_;
    Advance();
    if (tok_.kind == Tok::kLParen) return Call(name);
    if (name.text == "t") return pool_.Time();
    if (name.text == "pi") return pool_.Const(std::numbers::pi);
    if (name.text == "e") return pool_.Const(std::numbers::e);
    std::optional<NodeId> id;
    if (resolve_) id = resolve_(name.text, pool_);
    if (!id) throw ParseError("unknown name '" + std::string(name.text) + "'", name.offset);
    if (*id >= pool_.size())
      throw ParseError("name '" + std::string(name.text) + "' resolved to an invalid node",
                       name.offset);
    return *id;
  }

  NodeId Call(const Token& name) {
    const OpInfo* f = FindCallable(name.text);
    if (!f) throw ParseError("unknown function '" + std::string(name.text) + "'", name.offset);
    Advance();  // '(' (the arguments' Ternary calls count the nesting)
    std::vector<NodeId> args;
    if (tok_.kind != Tok::kRParen) {
      args.push_back(Ternary());
      while (tok_.kind == Tok::kComma) {
        Advance();
        args.push_back(Ternary());
      }
    }
    Expect(Tok::kRParen, "')'");
    const std::string fname(f->name);
    if (f->Has(kVariadic)) {
      if (args.empty())
        throw ParseError("function '" + fname + "' takes at least 1 argument", name.offset);
      NodeId acc = args[0];
      for (size_t i = 1; i < args.size(); ++i) acc = Binary(f->op, acc, args[i]);
      return acc;
    }
    if (static_cast<int>(args.size()) != f->arity) {
      throw ParseError("function '" + fname + "' takes " + std::to_string(f->arity) +
                           (f->arity == 1 ? " argument" : " arguments") + ", got " +
                           std::to_string(args.size()),
                       name.offset);
    }
    return pool_.Apply(f->op, args);
  }

  std::string_view text_;
  Pool& pool_;
  const Resolver& resolve_;
  size_t pos_ = 0;
  Token tok_;
  int depth_ = 0;
};

}  // namespace

NodeId Parse(std::string_view text, Pool& pool, const Resolver& resolve) {
  return Parser(text, pool, resolve).ParseAll();
}

}  // namespace asgard::expr
