/* METIS's partition of a mesh's dual graph for feps (feps_metis.f90): the elements into `parts`
 * parts of nearly equal weight, neighbours (elements that share `common` nodes) kept together.
 * The shim copies feps's 32-bit arrays into METIS's idx_t, whatever width this METIS was built
 * with. Returns 0, or 1 when METIS fails or memory runs out. */
#include <stdint.h>
#include <stdlib.h>
#include <metis.h>

int feps_metis_part_mesh_dual(int32_t elements, int32_t nodes, const int64_t *element_ptr,
                              const int32_t *element_nodes, const int32_t *weights, int32_t common,
                              int32_t parts, int32_t *part)
{
    idx_t ne = elements, nn = nodes, ncommon = common, nparts = parts, objval = 0;
    int64_t entries = element_ptr[elements];
    idx_t *eptr = malloc(sizeof(idx_t) * ((size_t)elements + 1));
    idx_t *eind = malloc(sizeof(idx_t) * (size_t)(entries > 0 ? entries : 1));
    idx_t *vwgt = malloc(sizeof(idx_t) * (size_t)(elements > 0 ? elements : 1));
    idx_t *epart = malloc(sizeof(idx_t) * (size_t)(elements > 0 ? elements : 1));
    idx_t *npart = malloc(sizeof(idx_t) * (size_t)(nodes > 0 ? nodes : 1));
    idx_t options[METIS_NOPTIONS];
    int status = 1;
    if (eptr && eind && vwgt && epart && npart) {
        for (int64_t i = 0; i <= elements; i++) eptr[i] = (idx_t)element_ptr[i];
        for (int64_t i = 0; i < entries; i++) eind[i] = (idx_t)element_nodes[i];
        for (int64_t i = 0; i < elements; i++) vwgt[i] = (idx_t)weights[i];
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_NUMBERING] = 0;
        if (METIS_PartMeshDual(&ne, &nn, eptr, eind, vwgt, NULL, &ncommon, &nparts, NULL, options, &objval,
                               epart, npart) == METIS_OK) {
            for (int64_t i = 0; i < elements; i++) part[i] = (int32_t)epart[i];
            status = 0;
        }
    }
    free(eptr);
    free(eind);
    free(vwgt);
    free(epart);
    free(npart);
    return status;
}
