# cmake -DINPUT=file -DOUTPUT=file.cpp -DSYMBOL=name -P embed_text.cmake: a text file as a C++
# string constant `extern const char* const wangscape::<SYMBOL>` (raw string literal).
file(READ "${INPUT}" content)
file(WRITE "${OUTPUT}.tmp" "// Generated from ${INPUT} by scene/embed_text.cmake; do not edit.\nnamespace wangscape {\nextern const char* const ${SYMBOL};\nconst char* const ${SYMBOL} = R\"embedded(${content})embedded\";\n}  // namespace wangscape\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
