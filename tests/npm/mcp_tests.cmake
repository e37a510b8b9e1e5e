# The official MCP TypeScript SDK as a client of `a3rig mcp`, over stdio and over Streamable
# HTTP (mcp_stdio.mjs, mcp_http.mjs): each installs the pinned SDK with install.sh and is
# skipped (exit 77) when npm cannot be used. Label "npm". Included from tests/npm/CMakeLists.txt.
# Arguments: the a3rig program and a scratch folder for the episodes.
find_program(A3_NODE node)
foreach(transport stdio http)
  add_test(NAME npm_mcp_${transport}
           COMMAND ${A3_NODE} ${CMAKE_CURRENT_LIST_DIR}/mcp_${transport}.mjs $<TARGET_FILE:a3rig>
                   ${CMAKE_CURRENT_BINARY_DIR}/mcp-scratch)
  set_tests_properties(npm_mcp_${transport} PROPERTIES SKIP_RETURN_CODE 77 LABELS npm TIMEOUT 600)
endforeach()
