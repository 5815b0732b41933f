"""The front end: preprocess a tab's text, lex it, parse it with the LALR tables into the syntax
tree (syntax), and print a tree back as GLSL (printer). Locations point into the user's files."""
