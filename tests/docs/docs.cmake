# cy_docs_tests(): the docs tests (ctest label "docs"), in the MSP430 trees, after every other
# test of the tree (they depend on all of them: one ordering instead of one per module). The
# top-level CMakeLists.txt defers the call to the end of the configuration, after the deferred
# tests (cy_board_flash_test) too:
# - docs.figures: the figures generated between markers in README.md and docs/*.md match the
#   measurements the tests just wrote (tools/doc_figures.py: cycle tables, image sizes, module
#   flash shares, the closed-loop table);
# - docs.commands (msp430 tree only): every command block marked to run in README.md and
#   docs/*.md runs as written from the repository root, board commands on the simulator
#   (tools/doc_commands.py; `make test` builds what they use: host, host-asan, fuzz, msp430).
# - hygiene.leftovers: last of all, no test of any tree left a process behind.
# The host trees check the marks (docs.marks) and the tools' --help (tools.help).
function(cy_tests_below dir out)
    get_property(tests DIRECTORY ${dir} PROPERTY TESTS)
    get_property(subs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    foreach(sub IN LISTS subs)
        cy_tests_below(${sub} more)
        list(APPEND tests ${more})
    endforeach()
    set(${out} ${tests} PARENT_SCOPE)
endfunction()

function(cy_docs_tests)
    set(tree msp430)
    if(CY_KERNELS STREQUAL "C")
        set(tree msp430-c)
    endif()
    add_test(NAME docs.figures
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/doc_figures.py
            --root ${PROJECT_SOURCE_DIR} --tree ${tree} --tree host --build ${CMAKE_BINARY_DIR}
            --host-bin ${CY_HOST_BIN_DIR})
    set(docs_tests docs.figures)
    if(tree STREQUAL "msp430")
        add_test(NAME docs.commands
            COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/doc_commands.py
                --root ${PROJECT_SOURCE_DIR})
        # after the figures (a block reruns target tests' listings and reads their reports)
        set_tests_properties(docs.commands PROPERTIES DEPENDS docs.figures RUN_SERIAL ON
            TIMEOUT 2400)
        list(APPEND docs_tests docs.commands)
    endif()
    set_tests_properties(${docs_tests} PROPERTIES LABELS docs)
    # The very last: no test of any tree left a process behind (make test runs the trees one
    # after the other, this one last).
    add_test(NAME hygiene.leftovers
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/docs/leftovers_test.py
            --build-root ${PROJECT_SOURCE_DIR}/build)
    set_tests_properties(hygiene.leftovers PROPERTIES LABELS hygiene RUN_SERIAL ON
        DEPENDS "${docs_tests}")

    # Every other test of the tree first.
    cy_tests_below(${PROJECT_SOURCE_DIR} all_tests)
    list(REMOVE_ITEM all_tests ${docs_tests} hygiene.leftovers)
    set_tests_properties(docs.figures PROPERTIES DEPENDS "${all_tests}")
endfunction()
