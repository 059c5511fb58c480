# The Wireshark Lua plugin (JAUS and Clearpath over UDP), generated at build
# time from the message descriptions by `jausctl msg wireshark`, so it never
# falls behind the codec (docs/wireshark.md). Installed where Debian's
# Wireshark loads global Lua plugins: <libdir>/wireshark/plugins
# (/usr/lib/x86_64-linux-gnu/wireshark/plugins with the /usr prefix of the .deb).
set(jaus_wireshark_plugin ${PROJECT_BINARY_DIR}/wireshark/jaus.lua)
add_custom_command(OUTPUT ${jaus_wireshark_plugin}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/wireshark
  COMMAND jausctl msg wireshark -o ${jaus_wireshark_plugin}
  DEPENDS jausctl
  COMMENT "Generating the Wireshark plugin wireshark/jaus.lua"
  VERBATIM)
add_custom_target(wireshark_plugin ALL DEPENDS ${jaus_wireshark_plugin})
install(FILES ${jaus_wireshark_plugin} DESTINATION ${CMAKE_INSTALL_LIBDIR}/wireshark/plugins)
