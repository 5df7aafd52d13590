# target: src/collide2d/toi/article_methods.hpp
# The seed wall method always takes the larger textbook root.
s|t = !(t_small < zero) ? t_small : t_large;|t = t_large;|
