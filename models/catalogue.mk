# The sample model catalogue: models from Debian's CGAL data package (libcgal-demo ships
# /usr/share/doc/libcgal-dev/data.tar.gz). Nothing here is committed data: `make models` extracts
# the files under build/models/.
#
# For each NAME in CATALOGUE:
#   NAME.src   the file's path inside data.tar.gz
#   NAME.opts  its bake options (modelc --help)

CGAL_DATA ?= /usr/share/doc/libcgal-dev/data.tar.gz
DEFAULT_MODEL := bunny00

CATALOGUE := bunny00 nefertiti head lion_head man fandisk b9_training kitten

bunny00.src := data/meshes/bunny00.off
bunny00.opts := --depth 8

nefertiti.src := data/meshes/nefertiti.off
nefertiti.opts := --depth 8

head.src := data/meshes/head.off
head.opts := --depth 8

lion_head.src := data/meshes/lion-head.off
lion_head.opts := --depth 8

man.src := data/meshes/man.off
man.opts := --depth 8 --up z

fandisk.src := data/meshes/fandisk.off
fandisk.opts := --depth 8

# point set with per-point colours (an aerial scan)
b9_training.src := data/points_3/b9_training.ply
b9_training.opts := --depth 8 --up z

# point set with normals
kitten.src := data/points_3/kitten.xyz
kitten.opts := --depth 7
