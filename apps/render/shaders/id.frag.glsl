// The id pass: each fish fragment writes its instance's id (FishDraw::ids) into an
// unsigned integer target; no shading, no blending.
flat in uint v_id;

out uint o_id;

void main() { o_id = v_id; }
