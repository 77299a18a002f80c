# PnEmbedKernels.cmake - embeds the OpenCL kernel sources into a C file at build time, so
# the OpenCL port reads no file at run time (issue 4).
#
#   cmake -DKERNEL_DIR=<kernels/> -DSOURCES=a.cl,b.cl -DOUT=<file.c> -P PnEmbedKernels.cmake
#
# Each .cl file becomes one self-contained source string: every `#include "name"` whose
# file is in KERNEL_DIR is replaced by that file, recursively, each file at most once per
# string (they all have include guards, so a repeat would be empty anyway), with #line
# directives so that build logs name the original file and line. Includes of files that
# are not in KERNEL_DIR stay as they are: the only one is penumbra/config.h in the C branch
# of pn_kernel.h, which an OpenCL compiler skips. A kernel header named like some other
# header on a device compiler's include path (PoCL puts the working directory first)
# therefore cannot shadow it: nothing is looked up when the program is built.
#
# The output holds the strings as byte arrays: C99 guarantees only 4095 characters in a
# string literal (-Woverlength-strings under -Wpedantic).

cmake_minimum_required(VERSION 3.25)

if(NOT KERNEL_DIR OR NOT SOURCES OR NOT OUT)
  message(FATAL_ERROR "PnEmbedKernels: pass -DKERNEL_DIR, -DSOURCES and -DOUT")
endif()
string(REPLACE "," ";" SOURCES "${SOURCES}")

# Appends to `acc` the text of `file` with its kernel-dir includes resolved. A work list of
# (file, position) frames replaces recursion; `seen` lists the files already inlined where
# nothing could leave them out. An include inside a conditional (#if/#ifdef/#ifndef beyond
# a header's own guard, in that file or in any file including it) may be compiled out by
# the configuration: pn_passes.h includes pn_occtex.h, and with it pn_nbuffer.h, only when
# PN_ENABLE_OCCTEX, and pn_mcsm.h includes pn_nbuffer.h again. So a file first inlined
# inside a conditional is inlined again at its next include (its include guard makes the
# copy empty when the first one was compiled), until an unconditional include marks it seen.
function(pn_embed_resolve root acc_var)
  set(acc "")
  set(seen "${root}")
  # cond_<depth>: open conditionals in that file's copied text beyond its guard; nested_<depth>:
  # whether some file below it on the stack was inside a conditional at its include.
  set(cond_0 0)
  set(nested_0 0)
  # Stack of files being expanded and, for each, the text still to copy.
  set(stack_files "${root}")
  file(READ "${KERNEL_DIR}/${root}" text0)
  set(text_0 "${text0}")
  set(line_0 1)
  set(depth 0)
  string(APPEND acc "#line 1 \"${root}\"\n")
  while(depth GREATER_EQUAL 0)
    set(text "${text_${depth}}")
    list(GET stack_files ${depth} cur)
    # First include line in the remaining text (anchored at a line start).
    string(REGEX MATCH "(^|\n)[ \t]*#[ \t]*include[ \t]*\"([A-Za-z0-9_./-]+)\"[^\n]*" m "${text}")
    if(NOT m)
      string(APPEND acc "${text}")
      if(NOT text MATCHES "\n$")
        string(APPEND acc "\n")
      endif()
      list(REMOVE_AT stack_files ${depth})
      math(EXPR depth "${depth} - 1")
      if(depth GREATER_EQUAL 0)
        list(GET stack_files ${depth} parent)
        # No newline: the parent's remaining text starts with the end of its include line.
        math(EXPR next "${line_${depth}} + 1")
        string(APPEND acc "#line ${next} \"${parent}\"")
      endif()
      continue()
    endif()
    set(name "${CMAKE_MATCH_2}")
    string(FIND "${text}" "${m}" pos)
    string(LENGTH "${m}" mlen)
    # Copy everything up to the include line (its leading newline included).
    if(m MATCHES "^\n")
      math(EXPR cut "${pos} + 1")
      math(EXPR mlen "${mlen} - 1")
    else()
      set(cut ${pos})
    endif()
    string(SUBSTRING "${text}" 0 ${cut} before)
    string(APPEND acc "${before}")
    math(EXPR after_start "${cut} + ${mlen}")
    string(SUBSTRING "${text}" ${after_start} -1 after)
    # line_<depth> is the line the remaining text starts on: the include's own line (its
    # newline is still ahead); the #line that resumes this file names the line after it.
    string(REGEX MATCHALL "\n" nls "${before}")
    list(LENGTH nls nl_count)
    # Conditionals opened and closed before the include (a header's guard counts as one).
    string(REGEX MATCHALL "\n[ \t]*#[ \t]*if" opens "\n${before}")
    string(REGEX MATCHALL "\n[ \t]*#[ \t]*endif" closes "\n${before}")
    list(LENGTH opens n_open)
    list(LENGTH closes n_close)
    math(EXPR cond_${depth} "${cond_${depth}} + ${n_open} - ${n_close}")
    math(EXPR at "${line_${depth}} + ${nl_count}")
    set(line_${depth} ${at})
    # Drop the rest of the include line (its newline stays with `after`).
    set(text_${depth} "${after}")
    string(SUBSTRING "${m}" 0 -1 directive)
    string(STRIP "${directive}" directive)
    if(EXISTS "${KERNEL_DIR}/${name}")
      list(FIND seen "${name}" already)
      list(FIND stack_files "${name}" cycle)
      if(already EQUAL -1 AND cycle EQUAL -1)
        set(guard 0)
        if(cur MATCHES "\\.h$")
          set(guard 1)
        endif()
        set(inner 0)
        if(nested_${depth} OR cond_${depth} GREATER guard)
          set(inner 1)
        else()
          list(APPEND seen "${name}")
        endif()
        list(APPEND stack_files "${name}")
        math(EXPR depth "${depth} + 1")
        set(cond_${depth} 0)
        set(nested_${depth} ${inner})
        file(READ "${KERNEL_DIR}/${name}" sub)
        set(text_${depth} "${sub}")
        set(line_${depth} 1)
        string(APPEND acc "#line 1 \"${name}\"\n")
      else()
        string(APPEND acc "/* ${name}: already included */")
      endif()
    else()
      string(APPEND acc "${directive}")
    endif()
  endwhile()
  set(${acc_var} "${acc}" PARENT_SCOPE)
endfunction()

set(body "/* Generated at build time by cmake/PnEmbedKernels.cmake from kernels/: ${SOURCES}.\n * Do not edit: edit the .cl and .h files in kernels/. */\n#include \"pn_cl_sources.h\"\n\n")
set(names "")
set(ptrs "")
set(index 0)
foreach(src IN LISTS SOURCES)
  pn_embed_resolve("${src}" text)
  # Bytes as a C initializer, 24 per line.
  string(HEX "${text}" hex)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
  string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){24})" "\\1\n    " bytes "${bytes}")
  string(APPEND body "static const unsigned char pn_cl_src_${index}[] = {\n    ${bytes}0x00};\n\n")
  string(APPEND names "    \"${src}\",\n")
  string(APPEND ptrs "    (const char *)pn_cl_src_${index},\n")
  math(EXPR index "${index} + 1")
endforeach()
string(APPEND body "const char *const pn_cl_sources[PN_CL_SOURCE_COUNT] = {\n${ptrs}};\n\n")
string(APPEND body "const char *const pn_cl_source_names[PN_CL_SOURCE_COUNT] = {\n${names}};\n")

list(LENGTH SOURCES count)
set(header "/* Generated by cmake/PnEmbedKernels.cmake. */\n#ifndef PN_CL_SOURCES_H\n#define PN_CL_SOURCES_H\n\n#define PN_CL_SOURCE_COUNT ${count}\nextern const char *const pn_cl_sources[PN_CL_SOURCE_COUNT];\nextern const char *const pn_cl_source_names[PN_CL_SOURCE_COUNT];\n\n#endif\n")

get_filename_component(out_dir "${OUT}" DIRECTORY)
# Write only on change, so dependants are not rebuilt for nothing.
foreach(pair "${OUT}|body" "${out_dir}/pn_cl_sources.h|header")
  string(REPLACE "|" ";" pair "${pair}")
  list(GET pair 0 path)
  list(GET pair 1 var)
  set(old "")
  if(EXISTS "${path}")
    file(READ "${path}" old)
  endif()
  if(NOT old STREQUAL "${${var}}")
    file(WRITE "${path}" "${${var}}")
  endif()
endforeach()
