// The table skyview finds by dlsym once it has loaded the module.
#include "entry_points.h"

extern "C" __attribute__((visibility("default"))) const skyview::detail::PclModule* skyview_pcl_module() {
  static const skyview::detail::PclModule table{skyview::detail::PclModuleBuild{}, &skyview::pcl_entry::read_cloud,
                                                &skyview::pcl_entry::statistical_inliers,
                                                &skyview::pcl_entry::morphological_ground};
  return &table;
}
