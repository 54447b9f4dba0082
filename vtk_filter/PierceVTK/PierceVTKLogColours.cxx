// VTK's logger (loguru) colours its messages with ANSI codes whenever TERM names a colour
// terminal, also when stderr goes to a file or a pipe (pvbatch in a script, ParaView's output
// captured by a test). Loading Pierce's filters turns the colours off when stderr is not a
// terminal, so warnings and errors read as plain text there; on a terminal nothing changes.
#include <cstdio>

#include <unistd.h>
#include <vtkloguru/loguru.hpp>

namespace {

struct PlainLogWhenNotATerminal {
  PlainLogWhenNotATerminal() {
    if (!isatty(fileno(stderr))) vtkloguru::g_colorlogtostderr = false;
  }
};

const PlainLogWhenNotATerminal plain_log_when_not_a_terminal;

}  // namespace
