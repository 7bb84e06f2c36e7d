# harness_names.cmake - the fuzz harnesses, one <name>.cpp each in this folder.
set(ARBOR_FUZZ_HARNESSES
  nrrd metaimage nifti vtk_image jpeg2000 dicom_file dicom_series multipart session transfer_functions)
