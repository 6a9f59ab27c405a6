# hc_ghdl_ieee_o2(<ghdl> <root> <backend label> <dep var> <options var>): a private copy of
# GHDL's ieee 2008 library compiled at -O2 under <root> (GHDL's packaged one is compiled
# without optimisation; numeric_std's "*" and "+" dominate the simulations, docs/performance.md).
# Sets <dep var> to the library index a custom command depends on and appends to <options var>
# the options that select it (--ieee=none -P<root>); leaves both unchanged when the switch
# HC_GHDL_OPT_IEEE is off or GHDL's sources (HC_IEEE2008_SRC) are not installed.
# A custom command's output cannot be a dependency in another directory, so each directory
# that simulates calls this once, with a <root> of its own.
function(hc_ghdl_ieee_o2 ghdl root label dep_var opt_var)
  if(NOT HC_GHDL_OPT_IEEE OR NOT EXISTS ${HC_IEEE2008_SRC}/numeric_std.vhdl)
    return()
  endif()
  set(files std_logic_1164 std_logic_1164-body std_logic_textio numeric_std numeric_std-body
      math_real math_real-body)
  list(TRANSFORM files PREPEND ${HC_IEEE2008_SRC}/)
  list(TRANSFORM files APPEND .vhdl)
  set(dir ${root}/ieee/v08)
  file(MAKE_DIRECTORY ${dir})
  set(dep ${dir}/ieee-obj08.cf)
  add_custom_command(OUTPUT ${dep}
    COMMAND ${ghdl} -a --std=08 -O2 --ieee=none --work=ieee --workdir=${dir} -Wno-hide ${files}
    WORKING_DIRECTORY ${dir}
    COMMENT "GHDL (${label}): compiling a private ieee library at -O2"
    VERBATIM)
  set(${dep_var} ${dep} PARENT_SCOPE)
  set(${opt_var} ${${opt_var}} --ieee=none -P${root} PARENT_SCOPE)
endfunction()
