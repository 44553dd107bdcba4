// A LinuxCNC program as read: one block a line, either an o-word statement
// (`o100 while [...]`, `o<name> call [1] [2]`) or words and parameter
// settings (`#1 = 2 G1 X#1`), with the o-word structure paired when the
// file is read (linuxcnc_reader.cpp).
#pragma once

#include "linuxcnc_expression.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sim::linuxcnc {

enum class Keyword {
  Sub,
  EndSub,
  Call,
  Return,
  While, // opens a loop, or closes a `do` of the same name
  EndWhile,
  Do,
  If,
  ElseIf,
  Else,
  EndIf,
  Repeat,
  EndRepeat,
  Break,
  Continue,
};

struct ParameterSetting {
  bool named = false;
  std::string name;  // named
  Expression number; // numbered: the parameter's number
  Expression value;
};

struct Word {
  char letter = 'g';
  Expression value;
};

struct Message {
  enum class Kind { Abort, Debug, Print, Msg };
  Kind kind = Kind::Debug;
  std::string text; // after the comma, as written
};

struct Block {
  enum class Kind { Empty, OWord, Words };
  Kind kind = Kind::Empty;
  int line = 0;
  std::string text; // the line as written, for messages

  // OWord
  std::string name; // `100` or `<name>`, lower case
  Keyword keyword = Keyword::Sub;
  std::optional<Expression> argument; // while, if, elseif, repeat, endsub, return
  std::vector<Expression> callArguments;
  // Pairing: While (loop), Do, Repeat: the block that ends the loop; a
  // closing While, EndWhile, EndRepeat: the block that opens it; If,
  // ElseIf: the next ElseIf, Else or EndIf; Else, ElseIf, EndIf: the EndIf
  // (`end`); Sub: its EndSub; Break, Continue: the loop's opening block;
  // Return: its Sub.
  std::size_t partner = 0;
  std::size_t end = 0;
  bool closesDo = false; // a While that ends a `do` loop

  // Words
  std::vector<ParameterSetting> settings;
  std::vector<Word> words;
  std::vector<Message> messages;

  LineContext context() const { return {line, text}; }
};

struct Program {
  std::vector<Block> blocks;
  std::map<std::string, std::size_t> subs; // name: its Sub block
  // The blocks run up to here (a closing `%`), else to the end of the file.
  bool endsWithPercent = false;
};

// Reads a whole LinuxCNC file; throws SimulationError at the first problem.
Program readLinuxcncProgram(std::string_view text);

std::string_view keywordName(Keyword keyword);

} // namespace cncc::backends::sim::linuxcnc
