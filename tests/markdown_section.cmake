# markdown_section.cmake: hc_markdown_section(<text> <heading> <out>) sets <out> to the part of
# the Markdown <text> under the line "<heading>" up to the next "## " heading, or fails naming
# <what> (the file, for the message) when there is no such line.
function(hc_markdown_section text heading what out)
  string(FIND "${text}" "\n${heading}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${what} has no section \"${heading}\"")
  endif()
  string(SUBSTRING "${text}" ${at} -1 section)
  string(SUBSTRING "${section}" 1 -1 section)
  string(FIND "${section}" "\n## " end)
  if(NOT end EQUAL -1)
    string(SUBSTRING "${section}" 0 ${end} section)
  endif()
  set(${out} "${section}" PARENT_SCOPE)
endfunction()
