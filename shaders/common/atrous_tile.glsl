// The work layout of an a-trous step in shared memory (SVGF's, svgf/atrous.glsl, and the learned
// denoiser's gated filter, neural/atrous_step.comp): the 5x5 taps of a workgroup's pixels, +-1 and
// +-2 steps away, on one dense tile of cells read from memory once. Declares the workgroup size;
// the dispatch is `threads` in passes/src/denoise/atrous_tile.rs.
//
// A workgroup of 16x16 invocations filters pixels `step` apart in y (one residue of y modulo
// `step`) and, in x, runs of `run` = min(step, 4) adjacent pixels `step` apart (run adjacent
// residues of x modulo `step`), so that the taps of all its pixels fall on a tile of 20 rows of
// `run` * (16 / run + 4) columns (20 for step 1, 24 for step 2, 32 from step 4 on): the
// workgroup's own pixels and a halo of two steps. A pixel's 25 taps are then 1.6 to 2.5 texels
// of each image read, instead of 25. The runs of 4 adjacent pixels keep the reads of large steps
// whole 32-byte sectors (a single residue would use 8 of every 32 bytes fetched). Cell (column,
// row) is pixel
//     origin + (column % run, 0) + step * (column / run, row),
// and invocation (x, y) filters cell (x + 2 run, y + 2). `step` is a power of two.
#ifndef LUCID_ATROUS_TILE_GLSL
#define LUCID_ATROUS_TILE_GLSL

#define ATROUS_GROUP 16
layout(local_size_x = ATROUS_GROUP, local_size_y = ATROUS_GROUP) in;

// The taps reach two steps beyond the workgroup's pixels.
const int ATROUS_HALO = 2;
const int ATROUS_ROWS = ATROUS_GROUP + 2 * ATROUS_HALO;
// The longest run of adjacent residues, and the widest tile (that of the longest run).
const int ATROUS_MAX_RUN = 4;
const int ATROUS_COLUMNS = ATROUS_MAX_RUN * (ATROUS_GROUP / ATROUS_MAX_RUN + 2 * ATROUS_HALO);

// Where a workgroup's tile lies (see the layout above). The step and the run are powers of two:
// their divisions are shifts.
struct AtrousTile {
    int step;
    ivec2 origin;
    int run;
    int run_shift;
    int columns;
};

AtrousTile atrous_tile(int step) {
    int step_shift = findLSB(step);
    AtrousTile tile;
    tile.step = step;
    tile.run = min(step, ATROUS_MAX_RUN);
    tile.run_shift = findLSB(tile.run);
    tile.columns = ATROUS_GROUP + 2 * ATROUS_HALO * tile.run;
    // Workgroups go through the step / run runs of residues first, then the tiles of each
    // residue's grid.
    int runs_shift = step_shift - tile.run_shift;
    ivec2 group = ivec2(gl_WorkGroupID.xy);
    ivec2 residue = ivec2((group.x & ((1 << runs_shift) - 1)) << tile.run_shift,
                          group.y & (step - 1));
    ivec2 first = ivec2((group.x >> runs_shift) * (ATROUS_GROUP >> tile.run_shift),
                        (group.y >> step_shift) * ATROUS_GROUP);
    tile.origin = residue + step * (first - ATROUS_HALO);
    return tile;
}

ivec2 atrous_cell_pixel(AtrousTile tile, ivec2 cell) {
    return tile.origin + ivec2(cell.x & (tile.run - 1), 0)
        + tile.step * ivec2(cell.x >> tile.run_shift, cell.y);
}

// The cell of this invocation's own pixel.
ivec2 atrous_own_cell(AtrousTile tile) {
    return ivec2(gl_LocalInvocationID.xy) + ivec2(ATROUS_HALO * tile.run, ATROUS_HALO);
}

// Where cell `cell` lies in a workgroup's shared arrays of ATROUS_ROWS * ATROUS_COLUMNS.
int atrous_cell_index(ivec2 cell) {
    return cell.y * ATROUS_COLUMNS + cell.x;
}

#endif
