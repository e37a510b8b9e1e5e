// Error messages of the DSDL codec (see serialization.hpp).
#include "bridge/dronecan/serialization.hpp"

namespace a3::bridge {

std::string CodecStatus::message(std::string_view type_name) const {
  std::string text(type_name);
  text += ": ";
  const std::string where = std::string("field '") + field + "'";
  switch (code) {
    case Code::kOk:
      return text + "ok";
    case Code::kArrayTooLong:
      return text + where + " has " + std::to_string(count) + " elements, at most " +
             std::to_string(limit);
    case Code::kPayloadTooShort:
      return text + "payload ends inside " + where;
    case Code::kTrailingBytes:
      return text + "payload has " + std::to_string(count) +
             " byte(s) after the last field";
    case Code::kBufferTooSmall:
      return text + "encoded form does not fit " + std::to_string(kMaxTransferPayloadBytes) +
             " bytes at " + where;
  }
  return text + "unknown error";
}

}  // namespace a3::bridge
