// The reference draw's fragment: one flat colour.
out vec4 o_colour;

void main() { o_colour = vec4(1.0); }
