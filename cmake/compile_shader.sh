#!/bin/sh
# Compiles one GLSL compute shader to a C header of SPIR-V words; quiet on success, the
# compiler's messages (and a failed build) on error. Usage: compile_shader.sh GLSLANG ARGS...
log=$(mktemp)
"$@" > "$log" 2>&1
status=$?
[ $status -ne 0 ] && cat "$log"
rm -f "$log"
exit $status
