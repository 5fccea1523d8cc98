/* Which instances a deformation kernel deforms, and where their outputs go. Build
 * option FF_INSTANCE_LIST (0/1; the host's ClJob::instance_list):
 *   0  instances 0 .. instances - 1, each read from and written to its own row: the
 *      NDRange's rows are ceil(instances / FF_INSTANCES_PER_ITEM).
 *   1  the instances a list names (a level of detail's, finflex/level_choice.hpp):
 *      output row i holds list entry i, list_entries[list_first + i], whose values,
 *      derived values and placement the kernel reads. The count is read on the device
 *      (list_counts[count_index], at most `instances`, the outputs' rows), so the host
 *      never waits for it: the NDRange has at most as many rows as the outputs and the
 *      work-items stride over the list (OpenCL 1.2 has no indirect dispatch); entries
 *      at or past `sources` (the instances the inputs hold) are skipped.
 * In a kernel: FF_INSTANCE_LIST_ARGUMENTS after its other arguments, then
 *   FF_EACH_INSTANCE_ROW { for each of the item's FF_INSTANCES_PER_ITEM instances:
 *                          const size_t instance = first_instance + k;   (the row)
 *                          if (instance >= listed) break;
 *                          FF_SOURCE_OR_SKIP(source)                      (the input) }
 * (`listed`: the rows to fill, read once.)
 * Every work-item of a work-group has the same rows (the groups that share local
 * memory are one row high), so the loops are uniform over a group. */
#ifndef FF_INSTANCE_LIST
#define FF_INSTANCE_LIST 0
#endif

#if FF_INSTANCE_LIST
#define FF_INSTANCE_LIST_ARGUMENTS                                                    \
  , __global const uint *restrict list_entries, const uint list_first,               \
      __global const uint *restrict list_counts, const uint count_index, const uint sources
#define FF_EACH_INSTANCE_ROW                                                           \
  for (size_t listed = min(list_counts[count_index], instances),                      \
              first_instance = get_global_id(1) * FF_INSTANCES_PER_ITEM;               \
       first_instance < listed; first_instance += get_global_size(1) * FF_INSTANCES_PER_ITEM)
#define FF_SOURCE_OR_SKIP(source)                                  \
  const size_t source = list_entries[list_first + instance];      \
  if (source >= sources) continue;
#else
#define FF_INSTANCE_LIST_ARGUMENTS
#define FF_EACH_INSTANCE_ROW                                                                     \
  for (size_t listed = instances, first_instance = get_global_id(1) * FF_INSTANCES_PER_ITEM,      \
              row_once = 1;                                                                      \
       row_once; row_once = 0)
#define FF_SOURCE_OR_SKIP(source) const size_t source = instance;
#endif
