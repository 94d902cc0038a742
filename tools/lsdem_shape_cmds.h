/* lsdem_shape_cmds.h -- subcommands of lsdem-shape that live in their own files
 * (tools/shape_<name>.c). Each takes the arguments after its name and returns the exit code
 * (0 ok, 1 failure with a message on stderr, 2 usage error). Register a new one with one line
 * here and one entry in the table in lsdem_shape.c's main(). */
#ifndef LSDEM_SHAPE_CMDS_H
#define LSDEM_SHAPE_CMDS_H

int cmd_render(int argc, char **argv);  /* shape_render.c */
int cmd_surface(int argc, char **argv); /* shape_render.c */

int cmd_from_labels(int argc, char **argv); /* shape_labels.c */
int cmd_to_raw(int argc, char **argv);      /* shape_image.c */
int cmd_from_mesh(int argc, char **argv);   /* shape_mesh.c */

int cmd_random(int argc, char **argv); /* shape_random.c */
int cmd_pack(int argc, char **argv);   /* shape_pack.c */

int cmd_membrane(int argc, char **argv); /* shape_membrane.c */
int cmd_net(int argc, char **argv);      /* shape_net.c */
int cmd_wall(int argc, char **argv);     /* shape_wall.c */
int cmd_terrain(int argc, char **argv);  /* shape_wall.c */
int cmd_voids(int argc, char **argv);    /* shape_voids.c */
int cmd_bands(int argc, char **argv);    /* shape_bands.c */

#endif
