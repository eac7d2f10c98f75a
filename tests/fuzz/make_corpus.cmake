# cmake -DSOURCE_DIR=<repo> -DCORPUS=<dir> -P make_corpus.cmake: copies the seed corpus of
# fuzz_scene into CORPUS (created; files already there, such as the fuzzer's own finds, are kept):
# data/scenes/*.json and tests/fuzz/seeds/* (3D scenes, scenes with "--set" lines).
if(NOT SOURCE_DIR OR NOT CORPUS)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<repo> -DCORPUS=<dir> -P make_corpus.cmake")
endif()
file(GLOB scenes ${SOURCE_DIR}/data/scenes/*.json)
file(GLOB seeds ${SOURCE_DIR}/tests/fuzz/seeds/*)
file(MAKE_DIRECTORY ${CORPUS})
file(COPY ${scenes} ${seeds} DESTINATION ${CORPUS})
list(LENGTH scenes n1)
list(LENGTH seeds n2)
message(STATUS "fuzz_scene corpus: ${n1} scenes and ${n2} seeds copied to ${CORPUS}")
