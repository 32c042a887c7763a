/*
 * Tri.h -- PQP 1.3's triangle record, as pqp-rs provides it.
 *
 * PQP_Model::tris is an array of these: the model's triangles in the order they were added, each
 * with the id given to AddTri. In the model's frame.
 */
#ifndef PQP_TRI_H
#define PQP_TRI_H

#include "PQP_Compile.h"

struct Tri
{
    PQP_REAL p1[3];
    PQP_REAL p2[3];
    PQP_REAL p3[3];
    int id;
};

#endif /* PQP_TRI_H */
