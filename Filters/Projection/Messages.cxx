// SPDX-License-Identifier: BSD-3-Clause
#include "Projection/Messages.h"

#include "vtkObject.h"
#include "vtkSetGet.h"

namespace mpvtk
{
void Messages::Warn(const std::string& text) const
{
  vtkWarningWithObjectMacro(this->Filter, << text);
}

void Messages::Error(const std::string& text) const
{
  vtkErrorWithObjectMacro(this->Filter, << text);
}

bool Messages::WarnOnce(const std::string& key, const std::string& text)
{
  if (!this->Warned.insert(key).second)
  {
    return false;
  }
  this->Warn(text);
  return true;
}
} // namespace mpvtk
