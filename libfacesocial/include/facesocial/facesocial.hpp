// Umbrella header: everything the library offers.
#pragma once

#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/decision.hpp"
#include "facesocial/detection.hpp"
#include "facesocial/detection_eval.hpp"
#include "facesocial/ehmm.hpp"
#include "facesocial/error.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/face_detector.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/observations.hpp"
#include "facesocial/open_set_eval.hpp"
#include "facesocial/skin_filter.hpp"
#include "facesocial/version.hpp"
