# Sourced by the IDE benchmarks: box_world FILE X Y Z writes a world of X*Y*Z grey Blinky Blocks
# filling its grid from the origin.
box_world() {
  cat > "$1" <<XML
<?xml version="1.0" encoding="UTF-8"?>
<world gridSize="$2,$3,$4" target="blinkyblocks" seed="1">
  <blockList color="128,128,128"><blocksBox origin="0,0,0" size="$2,$3,$4"/></blockList>
</world>
XML
}
