#version 330 core
// Shadow-map passes: depth only (the rasteriser writes gl_FragCoord.z).
void main() {}
