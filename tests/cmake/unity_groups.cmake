# The names a test file declares at file scope, and the check that the files of one unity group
# (one translation unit: tests/CMakeLists.txt, massspring_test_folder) do not clash on one.
#
# A file-scope name is one declared outside any class, function or doctest macro: in the global
# namespace, a named namespace or an anonymous one (an anonymous namespace's names count as the
# enclosing namespace's: they are found from it). What is recorded, with its namespace and line:
#   definition  a struct, class, union or enum with a body; a variable
#   function    a function with a body (its whole head, template parameters included)
#   alias       `using X = ...`, `using ns::X`, `typedef ... X`, `namespace X = ...`
#   macro       `#define X ...`
# Not recorded: forward declarations and prototypes (they may repeat), out-of-class member
# definitions (`A::f() {`), `using namespace`, static_assert, and what doctest's macros (TEST_CASE,
# TEST_SUITE, ...: names in upper case) enclose, which doctest keeps apart.
# Two files of a group clash on a name of one namespace unless
#   - both declare it as an alias (the compiler checks that both name the same thing),
#   - both define it as a function with different heads (overloads: C++ allows them), or
#   - both define it as the same macro, word for word.
# Anything else (a struct twice, a variable and a function, the same function twice, a macro with
# two bodies) is a clash: one translation unit cannot hold both, or a macro would change the
# meaning of the files after it.
#
# Run as a script, it checks the files given:
#   cmake -DGROUP=name "-DFILES=a.cpp;b.cpp" -P unity_groups.cmake
# (exit status non-zero, with the message, on a clash).

cmake_policy(VERSION 3.21)  # for script mode; include() keeps it to this file

# Characters that stand for ; [ ] and \ while a file's text is a CMake list, and the separator
# of a record's fields.
string(ASCII 1 _ms_semicolon)
string(ASCII 2 _ms_open_bracket)
string(ASCII 3 _ms_close_bracket)
string(ASCII 4 _ms_backslash)
string(ASCII 5 _ms_field)

# _ms_newlines(<out> <text>): only the line breaks of <text> (for keeping line numbers).
function(_ms_newlines out text)
  string(REGEX REPLACE "[^\n]" "" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# _ms_count_lines(<out> <text>): the number of line breaks in <text>.
function(_ms_count_lines out text)
  string(REGEX REPLACE "[^\n]" "" text "${text}")
  string(LENGTH "${text}" n)
  set(${out} ${n} PARENT_SCOPE)
endfunction()

# massspring_file_scope_names(<file> <out>): <out> is a list of records
# "kind<sep>name<sep>line<sep>namespace<sep>text" (sep: ASCII 5; namespace "a.b." for a::b, empty
# for the global one), one per declaration of a file-scope name of <file>.
function(massspring_file_scope_names file out)
  set(S "${_ms_semicolon}")
  set(B "${_ms_backslash}")
  set(F "${_ms_field}")
  get_filename_component(absolute "${file}" ABSOLUTE)  # relative to the current source folder
  file(READ "${absolute}" text)
  string(REPLACE ";" "${S}" text "${text}")
  string(REPLACE "[" "${_ms_open_bracket}" text "${text}")
  string(REPLACE "]" "${_ms_close_bracket}" text "${text}")
  string(REPLACE "\\" "${B}" text "${text}")
  # Tokens: raw strings, strings, characters, comments, preprocessor lines (with their
  # continuations), then runs of anything else. Each is replaced by what the scan needs.
  set(pattern "R\"\\(([^)]|\\)[^\"])*\\)\"")                  # R"( ... )"
  string(APPEND pattern "|\"([^\"${B}\n]|${B}.)*\"")           # "..."
  string(APPEND pattern "|'([^'${B}\n]|${B}.)*'")              # '.'
  string(APPEND pattern "|//[^\n]*")                           # // ...
  string(APPEND pattern "|/\\*([^*]|\\*+[^*/])*\\*+/")         # /* ... */
  string(APPEND pattern "|\n[ \t]*#([^\n]*${B}\n)*[^\n]*")     # a preprocessor line
  string(APPEND pattern "|[^\"'/R\n]+|.")
  string(REGEX MATCHALL "${pattern}" tokens "\n${text}")
  set(code "")
  set(records "")
  set(line 0)  # the text starts with the line break added above
  foreach(token IN LISTS tokens)
    string(SUBSTRING "${token}" 0 1 first)
    string(LENGTH "${token}" length)
    if(length GREATER 1 AND (token MATCHES "^R\"\\(" OR first STREQUAL "\"" OR
                             first STREQUAL "'"))
      _ms_newlines(breaks "${token}")
      string(APPEND code "\"\"${breaks}")
    elseif(token MATCHES "^//" OR token MATCHES "^/\\*")
      _ms_newlines(breaks "${token}")
      string(APPEND code " ${breaks}")
    elseif(token MATCHES "^\n[ \t]*#")
      _ms_count_lines(before "${code}")
      if(token MATCHES "^\n[ \t]*#[ \t]*define[ \t]+([A-Za-z_0-9]+)(.*)$")
        set(name "${CMAKE_MATCH_1}")
        string(REGEX REPLACE "${B}\n" " " body "${CMAKE_MATCH_2}")
        string(REGEX REPLACE "[ \t\n]+" " " body "${body}")
        string(STRIP "${body}" body)
        math(EXPR at "${before} + 1")
        list(APPEND records "macro${F}${name}${F}${at}${F}${F}#define ${name} ${body}")
      endif()
      _ms_newlines(breaks "${token}")
      string(APPEND code "${breaks}")
    else()
      string(APPEND code "${token}")
    endif()
  endforeach()

  # The code in chunks that each end at a brace; a stack holds what each open brace opened: "-"
  # anything but a namespace, "=" an anonymous namespace, "=a.b" namespace a::b. Anonymous
  # namespaces add nothing to the path of a name: their names are found from the enclosing one.
  string(REGEX MATCHALL "[^{}]*[{}]|[^{}]+$" chunks "${code}")
  set(stack "")
  set(at_namespace_scope 1)
  set(path "")
  set(line 0)
  foreach(chunk IN LISTS chunks)
    set(brace "")
    if(chunk MATCHES "[{}]$")
      string(REGEX REPLACE ".$" "" body "${chunk}")
      string(REGEX MATCH ".$" brace "${chunk}")
    else()
      set(body "${chunk}")
    endif()
    # The chunk's statements (split at ;) and, before a {, the head that opens it.
    string(REPLACE "${S}" ";" pieces "${body}")
    set(piece_line ${line})
    set(kind_of_brace "-")
    list(LENGTH pieces count)
    set(index 0)
    foreach(piece IN LISTS pieces)
      math(EXPR index "${index} + 1")
      _ms_count_lines(piece_breaks "${piece}")
      string(REGEX REPLACE "[^ \t\n].*$" "" lead "${piece}")
      _ms_count_lines(lead_breaks "${lead}")
      math(EXPR start "${piece_line} + ${lead_breaks}")
      math(EXPR piece_line "${piece_line} + ${piece_breaks}")
      string(REGEX REPLACE "[ \t\n]+" " " statement "${piece}")
      string(STRIP "${statement}" statement)
      set(whole "${statement}")
      # template <...> in front, up to two levels of <> inside
      string(REGEX REPLACE "^template ?<([^<>]|<([^<>]|<[^<>]*>)*>)*> ?" "" statement
        "${statement}")
      set(is_head 0)
      if(index EQUAL count AND brace STREQUAL "{")
        set(is_head 1)
      endif()
      set(kind "")
      set(name "")
      if(is_head)
        if(statement MATCHES "^(inline )?namespace ?([A-Za-z_0-9:]*)$")
          string(REPLACE "::" "." kind_of_brace "=${CMAKE_MATCH_2}")
        elseif(statement MATCHES "^extern \"\"$")
          set(kind_of_brace "=")
        elseif(NOT at_namespace_scope)
        elseif(statement MATCHES "^(struct|class|union|enum|enum class|enum struct) ([A-Za-z_0-9]+)( final)?( ?:[^(]*)?$")
          set(kind definition)
          set(name "${CMAKE_MATCH_2}")
        elseif(statement MATCHES "^[^(=]*[^A-Za-z_0-9:]([A-Za-z_][A-Za-z_0-9]*) ?(${_ms_open_bracket}[^=]*${_ms_close_bracket})? ?=")
          set(kind definition)  # a variable with a braced initialiser (or a lambda)
          set(name "${CMAKE_MATCH_1}")
        elseif(statement MATCHES "^([^(]*[^A-Za-z_0-9:])?([A-Za-z_][A-Za-z_0-9]*) ?\\(")
          set(name "${CMAKE_MATCH_2}")
          set(kind function)  # upper case: a doctest macro
          set(statement "${whole}")  # its template parameters make a different overload
          if(name MATCHES "^[A-Z0-9_]+$" OR name STREQUAL "operator")
            set(name "")
          endif()
        elseif(statement MATCHES "^[^(]*[^A-Za-z_0-9:]([A-Za-z_][A-Za-z_0-9]*)$")
          set(kind definition)  # a variable initialised with braces, T x{...}
          set(name "${CMAKE_MATCH_1}")
        endif()
      elseif(at_namespace_scope AND NOT statement STREQUAL "")
        if(statement MATCHES "^using namespace " OR statement MATCHES "^extern " OR
           statement MATCHES "^static_assert" OR statement MATCHES "^(struct|class|union|enum)[ A-Za-z_0-9:]*$")
        elseif(statement MATCHES "^namespace ([A-Za-z_0-9]+) ?=")
          set(kind alias)
          set(name "${CMAKE_MATCH_1}")
        elseif(statement MATCHES "^using ([A-Za-z_0-9]+) ?=")
          set(kind alias)
          set(name "${CMAKE_MATCH_1}")
        elseif(statement MATCHES "^using [A-Za-z_0-9:]*::([A-Za-z_0-9]+)$")
          set(kind alias)
          set(name "${CMAKE_MATCH_1}")
        elseif(statement MATCHES "^typedef .*[^A-Za-z_0-9]([A-Za-z_][A-Za-z_0-9]*)$")
          set(kind alias)
          set(name "${CMAKE_MATCH_1}")
        elseif(statement MATCHES "^[^(=]*[^A-Za-z_0-9:]([A-Za-z_][A-Za-z_0-9]*) ?(${_ms_open_bracket}[^=]*${_ms_close_bracket})? ?(=|$)")
          set(kind definition)  # a variable
          set(name "${CMAKE_MATCH_1}")
        endif()
      endif()
      if(NOT name STREQUAL "" AND NOT name MATCHES "^(const|constexpr|static|inline|return|auto)$")
        list(APPEND records "${kind}${F}${name}${F}${start}${F}${path}${F}${statement}")
      endif()
    endforeach()
    _ms_count_lines(breaks "${body}")
    math(EXPR line "${line} + ${breaks}")
    if(brace STREQUAL "{")
      list(APPEND stack ${kind_of_brace})
    elseif(brace STREQUAL "}")
      list(LENGTH stack depth)
      if(depth GREATER 0)
        list(REMOVE_AT stack -1)
      endif()
    endif()
    set(at_namespace_scope 1)
    set(path "")
    foreach(entry IN LISTS stack)
      if(entry STREQUAL "-")
        set(at_namespace_scope 0)
      elseif(NOT entry STREQUAL "=")
        string(SUBSTRING "${entry}" 1 -1 entry)
        string(APPEND path "${entry}.")
      endif()
    endforeach()
  endforeach()
  set(${out} "${records}" PARENT_SCOPE)
endfunction()

# massspring_check_unity_group(<group> <file>...): stops the configure step (FATAL_ERROR) when
# two of the files clash on a file-scope name, naming the group, the name and both files with
# their lines. Files are named as given.
function(massspring_check_unity_group group)
  set(F "${_ms_field}")
  foreach(file IN LISTS ARGN)
    massspring_file_scope_names("${file}" records)
    set(seen "")
    foreach(record IN LISTS records)
      string(REPLACE "${F}" ";" fields "${record}")
      list(GET fields 0 kind)
      list(GET fields 1 name)
      list(GET fields 2 line)
      list(GET fields 3 path)
      list(SUBLIST fields 4 -1 text)
      list(JOIN text ";" text)
      set(key "${path}${name}")
      if(key IN_LIST seen)
        continue()  # overloads and repeats within one file are that file's own business
      endif()
      list(APPEND seen "${key}")
      if(NOT DEFINED _file_${key})
        set(_file_${key} "${file}")
        set(_line_${key} "${line}")
        set(_kind_${key} "${kind}")
        set(_text_${key} "${text}")
        continue()
      endif()
      set(clash 1)
      if(kind STREQUAL "alias" AND _kind_${key} STREQUAL "alias")
        set(clash 0)  # the compiler checks that both name the same thing
      elseif(kind STREQUAL "function" AND _kind_${key} STREQUAL "function" AND
             NOT text STREQUAL _text_${key})
        set(clash 0)  # overloads
      elseif(kind STREQUAL "macro" AND _kind_${key} STREQUAL "macro" AND
             text STREQUAL _text_${key})
        set(clash 0)
      endif()
      if(clash)
        set(shown_first "${_text_${key}}")
        set(shown_second "${text}")
        foreach(shown shown_first shown_second)
          string(REPLACE "${_ms_semicolon}" ";" ${shown} "${${shown}}")
          string(REPLACE "${_ms_open_bracket}" "[" ${shown} "${${shown}}")
          string(REPLACE "${_ms_close_bracket}" "]" ${shown} "${${shown}}")
          string(REPLACE "${_ms_backslash}" "\\" ${shown} "${${shown}}")
        endforeach()
        string(REPLACE "." "::" qualified "${key}")
        message(FATAL_ERROR
          "unity group '${group}': the file-scope name '${qualified}' is declared in two of its "
          "files, which compile as one translation unit:\n"
          "  ${_file_${key}}:${_line_${key}}: ${shown_first}\n"
          "  ${file}:${line}: ${shown_second}\n"
          "Rename one of them (or set MASSSPRING_UNITY_TESTS=OFF to compile the files one by "
          "one).")
      endif()
    endforeach()
  endforeach()
endfunction()

if(CMAKE_SCRIPT_MODE_FILE STREQUAL CMAKE_CURRENT_LIST_FILE)
  if(NOT DEFINED GROUP OR NOT DEFINED FILES)
    message(FATAL_ERROR "usage: cmake -DGROUP=name \"-DFILES=a.cpp;b.cpp\" -P unity_groups.cmake")
  endif()
  massspring_check_unity_group("${GROUP}" ${FILES})
  message(STATUS "unity group '${GROUP}': no file-scope name declared twice")
endif()
